// The path render of `raylane render`: progress and ETA, --time, Ctrl-C, checkpoints and
// --resume, on one process or shared by the processes of an MPI job (docs/cluster.md).
#include <chrono>
#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include "aov_outputs.h"
#include "commands.h"
#include "pass_series.h"
#include "progress.h"
#include "raylane/core/strings.h"
#include "raylane/render/film/tile_share.h"
#include "region_option.h"
#include "render_request.h"

namespace raylane::cli {

namespace {

// Deals the tiles again when their measured costs say it pays (docs/cluster.md, "Balance").
// After this run's passes 2, 4, 8, 16, ... the processes sum their tiles' CPU seconds since the
// last check; rank 0 deals the tiles by largest cost first and keeps that table if it lowers
// the heaviest process's load by kWorthMoving of the mean or more. Then every process takes the
// whole film and keeps its new tiles' sums: the pixels' sums go on in the same order.
class Balancer {
 public:
  // Measured on this machine (docs/cluster.md, "Balance"): one tile's CPU time varies about
  // 5 % from pass to pass, so a gain of a few percent can be noise; 5 % cannot.
  static constexpr double kWorthMoving = 0.05;

  Balancer(const Cluster& cluster, TileBalance mode, TileShare start, Film& film)
      : cluster_(cluster), mode_(mode), share_(std::move(start)), film_(film) {}

  TileShare after_pass(const std::vector<double>& seconds) {
    if (cost_.empty()) cost_.assign(seconds.size(), 0.0);
    for (std::size_t t = 0; t < seconds.size(); ++t)
      cost_[t] += seconds[t];
    if (++passes_ < next_check_) return share_;
    next_check_ *= 2;
    cluster_.sum_tile_costs(cost_);
    std::vector<uint32_t> owner;
    if (cluster_.root()) owner = better_table();
    cluster_.broadcast(owner);
    std::fill(cost_.begin(), cost_.end(), 0.0);
    if (owner.empty()) return share_;
    for (std::size_t t = 0; t < owner.size(); ++t)
      tiles_moved_ += !owned_by(t, owner[t]);
    ++balances_;
    cluster_.share_film(film_);
    share_.owner = std::make_shared<const std::vector<uint32_t>>(std::move(owner));
    keep_share(film_, share_);
    return share_;
  }

  int tiles_moved() const { return tiles_moved_; }
  int balances() const { return balances_; }

 private:
  bool owned_by(std::size_t tile, uint32_t process) const {
    TileShare s = share_;
    s.index = process;
    return s.owns(tile);
  }

  // Rank 0: the new owner of each tile, or nothing if the tiles stay where they are.
  std::vector<uint32_t> better_table() const {
    std::vector<uint32_t> dealt = balance_tiles(cost_, share_.count);
    TileShare next = share_;
    next.owner = std::make_shared<const std::vector<uint32_t>>(dealt);
    double gain = imbalance(process_loads(cost_, share_)) - imbalance(process_loads(cost_, next));
    if (mode_ == TileBalance::kAlways || gain >= kWorthMoving) return dealt;
    return {};
  }

  const Cluster& cluster_;
  TileBalance mode_;
  TileShare share_;
  Film& film_;
  std::vector<double> cost_;  // thread-seconds per tile since the last check
  int passes_ = 0, next_check_ = 2, tiles_moved_ = 0, balances_ = 0;
};

// After each pass, every process takes part: each says whether it was interrupted; rank 0
// adds its clock (--time) and whether a checkpoint is due. All act on the same answer, so all
// stop after the same pass. A checkpoint assembles a copy of the film on rank 0.
class PassLoop {
 public:
  PassLoop(const RenderRequest& r, const Cluster& cluster, Film& film)
      : r_(r),
        cluster_(cluster),
        film_(film),
        progress_(r.path_settings.spp, r.path_settings.time_limit, r.quiet || !cluster.root()),
        checkpointer_(r.checkpoints),
        series_(r, cluster) {}

  void after_pass(int done) {
    PassControl mine;
    mine.interrupted = interrupted();
    if (cluster_.root()) {
      progress_.update(done);
      mine.checkpoint = checkpointer_.due();
      double limit = r_.path_settings.time_limit;
      mine.out_of_time = limit > 0 && seconds() >= limit;
    }
    double agreeing = seconds();
    busy_ += agreeing - last_agreed_;
    PassControl all = cluster_.agree(mine);
    last_agreed_ = seconds();
    wait_ += last_agreed_ - agreeing;
    if (all.checkpoint) save_checkpoint();
    interrupted_ |= all.interrupted;
    if (all.interrupted || all.out_of_time) stop_ = true;
    series_.after_pass(done, film_);
  }

  // --save-at: a resumed film may already hold a listed pass count.
  void start() { series_.start(film_); }
  bool series_failed() const { return series_.failed(); }
  const std::vector<SeriesSave>& series_saves() const { return series_.saves(); }

  bool interrupted_run() const { return interrupted_; }
  double wait_seconds() const { return wait_; }
  double busy_seconds() const { return busy_; }

  void finish() {
    int passes = film_.passes;
    cluster_.assemble(film_);
    if (cluster_.root()) checkpointer_.save(film_);
    progress_.finish();
    series_.finish(passes);
  }

  const std::atomic<bool>* stop_flag() const { return &stop_; }

 private:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

  void save_checkpoint() {
    if (!cluster_.distributed()) return checkpointer_.save(film_);
    Film whole = film_;  // this process's share; rank 0's copy receives the others'
    cluster_.assemble(whole);
    if (cluster_.root()) checkpointer_.save(whole);
  }

  const RenderRequest& r_;
  const Cluster& cluster_;
  Film& film_;
  Progress progress_;
  Checkpointer checkpointer_;
  PassSeries series_;
  std::atomic<bool> stop_{false};
  bool interrupted_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double last_agreed_ = 0, busy_ = 0, wait_ = 0;  // seconds since start_; summed
};

}  // namespace

PathOutcome run_path(const RenderRequest& r, const Tracer& tracer, const Cluster& cluster) {
  PathOutcome out;
  const Scene& scene = tracer.scene();
  auto film = starting_film(r.checkpoints, scene, r.path_settings);
  if (int bad = cluster.first_failure(film.ok()); bad >= 0) {
    if (!film) std::fprintf(stderr, "raylane: %s\n", film.error().c_str());
    if (bad > 0 && cluster.root())
      std::fprintf(stderr, "raylane: rank %d cannot use the --resume film\n", bad);
    out.status = kExitUsage;
    return out;
  }
  if (film->passes >= r.path_settings.spp && !r.quiet)
    std::fprintf(stderr,
                 "raylane: warning: the --resume film already holds %d passes and --spp asks "
                 "for %d: nothing to render; writing the film's image as it is\n",
                 film->passes, r.path_settings.spp);
  PathSettings settings = r.path_settings;
  settings.share = cluster.share();
  if (settings.region)
    settings.share = region_share(settings.share, *settings.region, scene.width, scene.height);
  if (cluster.distributed() && !film->sum.empty()) keep_share(*film, settings.share);
  PassLoop loop(r, cluster, *film);
  settings.time_limit = 0;  // the loop decides, on rank 0's clock, for every process
  settings.stop = loop.stop_flag();
  settings.on_pass = [&](int done) { loop.after_pass(done); };
  Balancer balancer(cluster, r.balance, settings.share, *film);
  if (cluster.distributed() && r.balance != TileBalance::kOff)
    settings.reshare = [&](const std::vector<double>& s) { return balancer.after_pass(s); };
  install_interrupt_handler(cluster.distributed());
  loop.start();
  render_path(tracer, settings, &out.stats, &*film);
  loop.finish();
  out.series_failed = loop.series_failed();
  out.series = loop.series_saves();
  cluster.sum(out.stats);
  double balance[2] = {loop.wait_seconds(), loop.busy_seconds()};
  cluster.sum_on_root(balance, 2);
  out.wait_seconds = balance[0], out.busy_seconds = balance[1];
  out.tiles_moved = balancer.tiles_moved(), out.balances = balancer.balances();
  out.interrupted = loop.interrupted_run();
  if (!cluster.root()) return out;
  out.film = std::move(*film);  // a --region's film holds the region alone
  return out;
}

void print_balance(const PathOutcome& run, int processes) {
  double all = run.wait_seconds + run.busy_seconds;
  std::fprintf(stderr,
               "  %d processes waited for the slowest after each pass: %.3f s of their %.3f s "
               "(%.1f %%)\n",
               processes, run.wait_seconds, all, all > 0 ? 100 * run.wait_seconds / all : 0.0);
  std::fprintf(stderr, "  tiles dealt again by measured cost: %s, %s moved\n",
               counted(run.balances, "time").c_str(), counted(run.tiles_moved, "tile").c_str());
}

}  // namespace raylane::cli
