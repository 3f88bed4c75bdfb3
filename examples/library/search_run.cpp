// A search of one's own on the softdrop library's service: a few generations of the default
// search on a small problem, logged to an SQLite history that `softdrop history` and Python's
// read_history read, each generation told to an observer. Run it again and it resumes the run.
// Built against an installed softdrop:
//   cmake --install build --prefix ~/.local
//   g++ -std=c++20 -O2 search_run.cpp -I ~/.local/include -L ~/.local/lib -lsoftdrop_service
//   -lsoftdrop_store -lsoftdrop_opt -lsoftdrop_studies -lsoftdrop_sim -lsoftdrop_media -lsoftdrop_util
//   -lSQLiteCpp -lsqlite3 -lpagmo -lnlopt -lcholmod -ltbb -lgmp -lmpfr -lpng -ltiff
//   ./a.out search.db 6      # a new run to generation 6, or run 1 resumed to it
// It is `softdrop optimize --db search.db --generations 6 --lambda 4 --starts 8 --validate-starts 0`,
// and stores the same history to the bit.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <softdrop/service.hpp>
#include <string>

namespace {

// Prints each stored generation; returning false would stop the run (it resumes later).
class Lines : public softdrop::SearchObserver {
 public:
  bool generation(std::int64_t run, int, const softdrop::Generation& g, const softdrop::Configuration& best,
                  std::int64_t target) override {
    std::printf("run %lld generation %lld/%lld best T %.6f\n", static_cast<long long>(run),
                static_cast<long long>(g.number), static_cast<long long>(target), best.eval.tortuosity);
    return true;
  }
};

}  // namespace

int main(int argc, char** argv) {
  softdrop::SearchRun run;
  run.db = argc > 1 ? argv[1] : "search.db";
  run.generations = argc > 2 ? std::atoll(argv[2]) : 6;
  run.resume = std::filesystem::exists(run.db) ? 1 : 0;  // the file's first run, continued
  // The program's default search (its strategy, relocation and objective), smaller: 4 candidates
  // a generation, each scored by the mean T of 8 droplets from fresh starts.
  run.search.strategy.kind = softdrop::StrategyKind::es;
  run.search.relocate_every = 3;
  run.search.objective.kind = softdrop::ObjectiveKind::mean;
  run.search.objective.starts = 8;
  run.search.lambda = 4;
  run.start.medium.kind = softdrop::MediumKind::non_overlapping;
  run.start.medium.grains = 20;
  run.validate_starts = 0;  // `softdrop validate` gives it later
  Lines lines;
  try {
    const softdrop::SearchRunSummary s = softdrop::run_search(run, lines);
    std::printf("%s: run %lld, %s\nbest T %.17g at generation %lld\n", run.db.c_str(), static_cast<long long>(s.run),
                s.nothing_to_do ? "nothing to do" : s.drive.message.c_str(), s.best.eval.tortuosity,
                static_cast<long long>(s.best.generation));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "search_run: %s\n", e.what());
    return 1;
  }
  return 0;
}
