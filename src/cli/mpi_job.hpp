#pragma once
// This process as one rank of an MPI job (started by mpirun, or by srun under Slurm). The program
// initialises MPI only when a launcher started it, so that without one it is the plain program.
// MPI is process-wide, hence one Job per process, reached through current_job().

#include <exception>
#include <string>
#include <vector>

namespace softdrop::cli {

/// True when an MPI launcher started this process (its environment names a rank: OpenMPI's
/// OMPI_COMM_WORLD_RANK, PMIx's PMIX_RANK or PMI's PMI_RANK).
bool launched_by_mpi();

/// The ranks the launcher says the job has (OMPI_COMM_WORLD_SIZE or PMI_SIZE); 1 if it does not say.
int launched_ranks();

/// Whether this program was built with MPI.
bool built_with_mpi();

class Job {
 public:
  /// Initialises MPI (threads: serialised calls). Throws std::runtime_error if the build has no
  /// MPI, or MPI cannot give the thread support the sweep needs.
  Job(int* argc, char*** argv);
  ~Job();  ///< finalises MPI
  Job(const Job&) = delete;
  Job& operator=(const Job&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Ends every rank of the job with `code` (for an error that leaves the others waiting).
  [[noreturn]] void abort(int code) const;
  /// Reports `e` on stderr with this rank, then ends the job (abort(1)).
  [[noreturn]] void fail(const std::exception& e) const;

 private:
  int rank_ = 0, size_ = 1;
};

/// The job of this process; nullptr when no launcher started it.
Job* current_job();

/// Message passing for one job, with every call serialised by one lock (the worker threads and
/// the calling thread of a rank both send). Tags keep the kinds of message apart.
namespace mpi {
void send(int to, int tag, const std::string& bytes);
/// Blocks for the next message of `tag` from `from` (any sender, any tag if negative); sets the
/// sender and the tag it had.
std::string receive(int from, int tag, int* sender = nullptr, int* received_tag = nullptr);
/// Rank 0's `values` to every rank (the others' are replaced).
void broadcast(std::vector<int>& values);
}  // namespace mpi

}  // namespace softdrop::cli
