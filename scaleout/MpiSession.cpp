#include "scaleout/MpiSession.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdlib>

#include "common/Error.h"

#ifdef BAKER_HAVE_MPI
#include <mpi.h>
#endif

namespace baker {

#ifdef BAKER_HAVE_MPI

namespace {
// Floats per message: well inside MPI's int count, and 1 GiB at most in flight.
constexpr std::size_t kPieceFloats = std::size_t(1) << 28;
constexpr int kValuesTag = 7;
}  // namespace

bool mpiAvailable() { return true; }

MpiSession::MpiSession() {
  MPI_Init(nullptr, nullptr);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, rank_, MPI_INFO_NULL, &node);
  MPI_Comm_size(node, &local_);
  MPI_Comm_free(&node);
}

MpiSession::~MpiSession() { MPI_Finalize(); }

void MpiSession::abort(int exitCode) const {
  MPI_Abort(MPI_COMM_WORLD, exitCode);
  std::exit(exitCode);  // MPI_Abort does not return; this keeps [[noreturn]] true if it did
}

void MpiSession::sendToRoot(const std::vector<float>& values) const {
  for (std::size_t start = 0; start < values.size(); start += kPieceFloats)
    MPI_Send(values.data() + start, int(std::min(kPieceFloats, values.size() - start)), MPI_FLOAT, 0, kValuesTag,
             MPI_COMM_WORLD);
}

void MpiSession::receiveFrom(int from, std::vector<float>& values) const {
  for (std::size_t start = 0; start < values.size(); start += kPieceFloats) {
    const int count = int(std::min(kPieceFloats, values.size() - start));
    MPI_Status status;
    MPI_Recv(values.data() + start, count, MPI_FLOAT, from, kValuesTag, MPI_COMM_WORLD, &status);
    int received = 0;
    MPI_Get_count(&status, MPI_FLOAT, &received);
    if (received != count)
      throw InputError(fmt::format("rank {} sent {} values where {} were expected", from, received, count));
  }
}

std::vector<double> MpiSession::gatherToRoot(const std::vector<double>& values) const {
  std::vector<double> all(rank_ == 0 ? values.size() * std::size_t(size_) : 0);
  MPI_Gather(values.data(), int(values.size()), MPI_DOUBLE, all.data(), int(values.size()), MPI_DOUBLE, 0,
             MPI_COMM_WORLD);
  return all;
}

#else

bool mpiAvailable() { return false; }

MpiSession::MpiSession() {
  throw SettingError("mpi",
                     "needs a baker built with Open MPI: install Debian's libopenmpi-dev and openmpi-bin "
                     "(scripts/install-deps.sh does), then build again; or bake parts with shards and merge them");
}
MpiSession::~MpiSession() = default;
void MpiSession::abort(int exitCode) const { std::exit(exitCode); }
void MpiSession::sendToRoot(const std::vector<float>&) const {}
void MpiSession::receiveFrom(int, std::vector<float>&) const {}
std::vector<double> MpiSession::gatherToRoot(const std::vector<double>& values) const { return values; }

#endif

}  // namespace baker
