// One render across the processes that `mpirun` started (docs/cluster.md): each renders its
// share of the tiles for every pass, all of them agree after each pass on whether to stop
// or save a checkpoint, and rank 0 assembles the films and writes every file.
//
// Started without a launcher, raylane never calls MPI (not even MPI_Init): the environment
// tells, before any MPI call, whether a launcher started this process.
#pragma once

#include "raylane/render/film/film.h"
#include "raylane/render/path.h"

#include <cstdint>
#include <vector>

namespace raylane::cli {

// What every process does after a pass: each one's wish, OR-ed over all of them.
struct PassControl {
  bool interrupted = false;  // Ctrl-C (SIGINT) somewhere
  bool out_of_time = false;  // the --time budget, on rank 0's clock
  bool checkpoint = false;   // rank 0's --checkpoint-every is due
};

class Cluster {
 public:
  Cluster();  // joins the MPI job if a launcher started this process
  ~Cluster();
  Cluster(const Cluster&) = delete;
  Cluster& operator=(const Cluster&) = delete;

  bool distributed() const { return size_ > 1; }
  bool root() const { return rank_ == 0; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  TileShare share() const { return {uint32_t(rank_), uint32_t(size_), nullptr}; }

  // The lowest rank for which `ok` is false, or −1 if it holds on every process.
  int first_failure(bool ok) const;
  PassControl agree(PassControl mine) const;
  // Every process's sums gathered into rank 0's `film`. Their tiles are disjoint: every other
  // process holds +0.0 (all bits clear) where one holds a sum, so a bitwise OR of the doubles'
  // bits gives that sum exactly, in any order, whatever its bits (−0.0 and NaN included; an
  // arithmetic sum would turn −0.0 + 0.0 into +0.0). Other ranks' films are unchanged.
  void assemble(Film& film) const;
  // Every process's `film` becomes the whole film (as assemble, on all processes): before
  // tiles change hands, so that each process holds the sums of the tiles it takes.
  void share_film(Film& film) const;
  // Each process's tile costs (zero outside its own tiles) summed on every process: exact, as
  // the supports are disjoint.
  void sum_tile_costs(std::vector<double>& tile_cost) const;
  // Rank 0's `owner` table on every process (resized to rank 0's size).
  void broadcast(std::vector<uint32_t>& owner) const;
  void sum(PathStats& stats) const;               // counters and phase times summed into rank 0's
  void sum_on_root(double* values, int n) const;  // each value summed into rank 0's
  // Rank 0's exit status, on every process (so that mpirun reports what rank 0 decided).
  int root_status(int status) const;

 private:
  bool mpi_ = false;
  int rank_ = 0, size_ = 1;
};

// Whether a process launcher started this process (Open MPI, MPICH or any PMI/PMIx one).
bool started_by_launcher();

}  // namespace raylane::cli
