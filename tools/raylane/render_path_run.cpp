// The path render of `raylane render`: progress and ETA, --time, Ctrl-C, checkpoints and
// --resume, on one process or shared by the processes of an MPI job (docs/cluster.md).
#include <chrono>
#include <cstdio>

#include "aov_outputs.h"
#include "commands.h"
#include "progress.h"
#include "raylane/core/strings.h"
#include "render_request.h"

namespace raylane::cli {

namespace {

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
        checkpointer_(r.checkpoints) {}

  void after_pass(int done) {
    PassControl mine;
    mine.interrupted = interrupted();
    if (cluster_.root()) {
      progress_.update(done);
      mine.checkpoint = checkpointer_.due();
      double limit = r_.path_settings.time_limit;
      mine.out_of_time = limit > 0 && seconds() >= limit;
    }
    PassControl all = cluster_.agree(mine);
    if (all.checkpoint) save_checkpoint();
    interrupted_ |= all.interrupted;
    if (all.interrupted || all.out_of_time) stop_ = true;
  }

  bool interrupted_run() const { return interrupted_; }

  void finish() {
    cluster_.assemble(film_);
    if (cluster_.root()) checkpointer_.save(film_);
    progress_.finish();
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
  std::atomic<bool> stop_{false};
  bool interrupted_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
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
  if (cluster.distributed() && !film->sum.empty()) keep_share(*film, settings.share);
  PassLoop loop(r, cluster, *film);
  settings.time_limit = 0;  // the loop decides, on rank 0's clock, for every process
  settings.stop = loop.stop_flag();
  settings.on_pass = [&](int done) { loop.after_pass(done); };
  install_interrupt_handler(cluster.distributed());
  render_path(tracer, settings, &out.stats, &*film);
  loop.finish();
  cluster.sum(out.stats);
  out.interrupted = loop.interrupted_run();
  if (!cluster.root()) return out;
  out.image = film->image();
  for (const auto& [path, aov] : r.aov_outputs)
    out.aov_images.emplace_back(path, film->aov_image(aov));
  out.exr_layers = exr_layers_of(*film);
  return out;
}

}  // namespace raylane::cli
