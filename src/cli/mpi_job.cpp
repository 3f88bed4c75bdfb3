#include "cli/mpi_job.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>

#ifdef SOFTDROP_HAVE_MPI
#include <mpi.h>
#endif

namespace softdrop::cli {
namespace {
Job* g_job = nullptr;
}  // namespace

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

int launched_ranks() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* v = std::getenv(name)) return std::max(1, std::atoi(v));
  return 1;
}

Job* current_job() { return g_job; }

#ifdef SOFTDROP_HAVE_MPI
namespace {
std::mutex g_calls;  // MPI_THREAD_SERIALIZED: one call at a time in this process

void check(int code, const char* what) {
  if (code != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + what + " failed");
}
}  // namespace

bool built_with_mpi() { return true; }

Job::Job(int* argc, char*** argv) {
  int provided = 0;
  check(MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  g_job = this;
  if (provided < MPI_THREAD_SERIALIZED)
    throw std::runtime_error("MPI: this MPI library cannot serve calls from several threads (MPI_THREAD_SERIALIZED)");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Job::~Job() {
  g_job = nullptr;
  MPI_Finalize();
}

void Job::abort(int code) const {
  MPI_Abort(MPI_COMM_WORLD, code);
  std::_Exit(code);
}

namespace mpi {
void send(int to, int tag, const std::string& bytes) {
  std::lock_guard lock(g_calls);
  check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, to, tag, MPI_COMM_WORLD), "MPI_Send");
}

std::string receive(int from, int tag, int* sender, int* received_tag) {
  // Polled, with sleeps that grow to 2 ms: a blocking probe spins on a core, which rank 0 needs
  // for its own units (its messages come seconds apart), and the lock stays free between polls.
  MPI_Status status;
  for (auto pause = std::chrono::microseconds(20);; pause = std::min(2 * pause, std::chrono::microseconds(2000))) {
    {
      std::lock_guard lock(g_calls);
      int found = 0;
      check(MPI_Iprobe(from < 0 ? MPI_ANY_SOURCE : from, tag < 0 ? MPI_ANY_TAG : tag, MPI_COMM_WORLD, &found, &status),
            "MPI_Iprobe");
      if (found) break;
    }
    std::this_thread::sleep_for(pause);
  }
  std::lock_guard lock(g_calls);
  int count = 0;
  MPI_Get_count(&status, MPI_BYTE, &count);
  std::string bytes(static_cast<std::size_t>(count), '\0');
  check(MPI_Recv(bytes.data(), count, MPI_BYTE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE),
        "MPI_Recv");
  if (sender) *sender = status.MPI_SOURCE;
  if (received_tag) *received_tag = status.MPI_TAG;
  return bytes;
}

void broadcast(std::vector<int>& values) {
  std::lock_guard lock(g_calls);
  int n = static_cast<int>(values.size());
  check(MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
  values.resize(static_cast<std::size_t>(n));
  check(MPI_Bcast(values.data(), n, MPI_INT, 0, MPI_COMM_WORLD), "MPI_Bcast");
}
}  // namespace mpi

#else  // built without MPI: a launched program says so; nothing else reaches these

bool built_with_mpi() { return false; }

Job::Job(int*, char***) {
  throw std::runtime_error(
      "this softdrop was built without MPI (install libopenmpi-dev and rebuild), so it cannot run "
      "as one of several ranks; run it without mpirun, or use --shard i/n and sweep-merge");
}
Job::~Job() = default;
void Job::abort(int code) const { std::_Exit(code); }

namespace mpi {
void send(int, int, const std::string&) { throw std::logic_error("MPI: not built"); }
std::string receive(int, int, int*, int*) { throw std::logic_error("MPI: not built"); }
void broadcast(std::vector<int>&) { throw std::logic_error("MPI: not built"); }
}  // namespace mpi
#endif

// An error on one rank leaves the others waiting for it: it ends the whole job.
void Job::fail(const std::exception& e) const {
  std::fprintf(stderr, "softdrop: error (rank %d): %s\n", rank(), e.what());
  abort(1);
}

}  // namespace softdrop::cli
