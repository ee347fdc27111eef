#pragma once
#include <cstdint>
#include <vector>

namespace baker {

// Whether this baker was built with Open MPI (CMake found it): without it, MpiSession refuses.
bool mpiAvailable();

// One process's part in an MPI job (mpirun -np N baker ... --mpi): MPI is initialised for the
// session's lifetime. Ranks exchange only what a bake needs: floats from a rank to rank 0, and
// a few numbers from every rank.
class MpiSession {
 public:
  // SettingError("mpi") saying how to get Open MPI when baker was built without it.
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Ranks of this job on this machine (sharing its cores).
  int ranksOnThisMachine() const { return local_; }

  // Stops every rank of the job with `exitCode`: a rank that failed must not leave the others
  // waiting for its values.
  [[noreturn]] void abort(int exitCode) const;

  // Rank `from` sends `values` (whose size both sides know) to rank 0, in pieces that MPI's int
  // counts can hold.
  void sendToRoot(const std::vector<float>& values) const;
  void receiveFrom(int from, std::vector<float>& values) const;
  // Every rank's `values` (the same count on each), rank after rank, on rank 0; empty elsewhere.
  std::vector<double> gatherToRoot(const std::vector<double>& values) const;

 private:
  int rank_ = 0, size_ = 1, local_ = 1;
};

}  // namespace baker
