#include "cluster.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#ifdef RAYLANE_HAVE_MPI
#include <mpi.h>
#endif

namespace raylane::cli {

bool started_by_launcher() {
  // Open MPI's mpirun sets OMPI_COMM_WORLD_SIZE; Hydra (MPICH) and Slurm set PMI_SIZE; PMIx
  // launchers set PMIX_RANK.
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

#ifdef RAYLANE_HAVE_MPI

namespace {

// MPI counts are ints: long buffers go in chunks.
constexpr std::size_t kChunk = std::size_t(1) << 26;

// A film's doubles as their bits, OR-ed over the processes into rank 0's (to_all: into
// every process's).
void reduce_bits(std::vector<double>& column, bool root, bool to_all) {
  static_assert(sizeof(double) == sizeof(uint64_t));
  for (std::size_t at = 0; at < column.size(); at += kChunk) {
    int count = int(std::min(kChunk, column.size() - at));
    void* data = column.data() + at;
    if (to_all)
      MPI_Allreduce(MPI_IN_PLACE, data, count, MPI_UINT64_T, MPI_BOR, MPI_COMM_WORLD);
    else if (root)
      MPI_Reduce(MPI_IN_PLACE, data, count, MPI_UINT64_T, MPI_BOR, 0, MPI_COMM_WORLD);
    else
      MPI_Reduce(data, nullptr, count, MPI_UINT64_T, MPI_BOR, 0, MPI_COMM_WORLD);
  }
}

}  // namespace

Cluster::Cluster() {
  if (!started_by_launcher()) return;
  MPI_Init(nullptr, nullptr);
  mpi_ = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

Cluster::~Cluster() {
  if (mpi_) MPI_Finalize();
}

int Cluster::first_failure(bool ok) const {
  if (!mpi_) return ok ? -1 : 0;
  int mine = ok ? size_ : rank_, lowest = size_;
  MPI_Allreduce(&mine, &lowest, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return lowest == size_ ? -1 : lowest;
}

PassControl Cluster::agree(PassControl mine) const {
  if (!mpi_) return mine;
  int wish[3] = {mine.interrupted, mine.out_of_time, mine.checkpoint}, all[3] = {0, 0, 0};
  MPI_Allreduce(wish, all, 3, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return {all[0] != 0, all[1] != 0, all[2] != 0};
}

int Cluster::root_status(int status) const {
  if (!mpi_) return status;
  MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
  return status;
}

void Cluster::assemble(Film& film) const {
  if (!mpi_ || size_ == 1) return;
  reduce_bits(film.sum, root(), false);
  reduce_bits(film.aov_sum, root(), false);
}

void Cluster::share_film(Film& film) const {
  if (!mpi_ || size_ == 1) return;
  reduce_bits(film.sum, root(), true);
  reduce_bits(film.aov_sum, root(), true);
}

void Cluster::sum_tile_costs(std::vector<double>& tile_cost) const {
  if (!mpi_ || size_ == 1) return;
  for (std::size_t at = 0; at < tile_cost.size(); at += kChunk) {
    int count = int(std::min(kChunk, tile_cost.size() - at));
    MPI_Allreduce(MPI_IN_PLACE, tile_cost.data() + at, count, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  }
}

void Cluster::broadcast(std::vector<uint32_t>& owner) const {
  if (!mpi_ || size_ == 1) return;
  uint64_t n = owner.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, MPI_COMM_WORLD);
  owner.resize(n);
  for (std::size_t at = 0; at < n; at += kChunk)
    MPI_Bcast(owner.data() + at, int(std::min<uint64_t>(kChunk, n - at)), MPI_UINT32_T, 0,
              MPI_COMM_WORLD);
}

void Cluster::sum_on_root(double* values, int n) const {
  if (!mpi_ || size_ == 1) return;
  if (root())
    MPI_Reduce(MPI_IN_PLACE, values, n, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  else
    MPI_Reduce(values, nullptr, n, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
}

void Cluster::sum(PathStats& s) const {
  if (!mpi_ || size_ == 1) return;
  uint64_t counts[5] = {s.camera_rays, s.bounce_rays, s.shadow_rays, s.nonfinite_samples, s.steps};
  double phases[6] = {s.phases.camera, s.phases.trace_camera, s.phases.trace_rest,
                      s.phases.shade,  s.phases.lights,       s.phases.film};
  if (root()) {
    MPI_Reduce(MPI_IN_PLACE, counts, 5, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    MPI_Reduce(MPI_IN_PLACE, phases, 6, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  } else {
    MPI_Reduce(counts, nullptr, 5, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    MPI_Reduce(phases, nullptr, 6, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
  }
  s.camera_rays = counts[0], s.bounce_rays = counts[1], s.shadow_rays = counts[2];
  s.nonfinite_samples = counts[3], s.steps = counts[4];
  s.phases = {phases[0], phases[1], phases[2], phases[3], phases[4], phases[5]};
}

#else  // built without MPI: always a single process

Cluster::Cluster() = default;
Cluster::~Cluster() = default;
int Cluster::first_failure(bool ok) const {
  return ok ? -1 : 0;
}
PassControl Cluster::agree(PassControl mine) const {
  return mine;
}
int Cluster::root_status(int status) const {
  return status;
}
void Cluster::assemble(Film&) const {}
void Cluster::share_film(Film&) const {}
void Cluster::sum_tile_costs(std::vector<double>&) const {}
void Cluster::broadcast(std::vector<uint32_t>&) const {}
void Cluster::sum(PathStats&) const {}
void Cluster::sum_on_root(double*, int) const {}

#endif

}  // namespace raylane::cli
