#pragma once
// The speculative pipeline under drive() (drive.cpp): worker threads evaluate the candidates of
// later generations before the earlier ones complete, each from the strategy state the pipeline
// expects its generation to have, and predict acceptances, so that every thread and lane stays
// busy. The history is that of one generation at a time: the same bits as Search::next.
#include <cstdint>
#include <memory>

#include "softdrop/search.hpp"

namespace softdrop {

class SpeculativePipeline {
 public:
  /// Starts `workers` threads, each stepping `lanes` candidates together, on the generations after
  /// search's last, up to `last_allowed`. Only for a strategy whose generations it can foresee
  /// (Strategy::speculative) and a single-start objective.
  SpeculativePipeline(Search& search, int workers, int lanes, std::int64_t last_allowed);
  /// Stops the workers; candidates still running are cancelled.
  ~SpeculativePipeline();
  SpeculativePipeline(const SpeculativePipeline&) = delete;
  SpeculativePipeline& operator=(const SpeculativePipeline&) = delete;
  /// The next generation, completed in the search (as Search::next would).
  Generation next();
  /// The speculation's counts so far (threads and lanes are the caller's to fill in).
  SpeculationStats stats();

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace softdrop
