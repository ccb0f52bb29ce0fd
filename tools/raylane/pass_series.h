// `raylane render --save-at LIST`: the report's pass series (the course framework wrote
// Image_Pass_N.hdr). During one path render the image is written after each listed pass, as
// STEM.N.EXT beside each output (room.hdr → room.16.hdr), each file the one `raylane render
// --spp N -o STEM.N.EXT` writes, bit for bit: the film after N passes is the film of a render
// stopped at N, and the header says RAYLANE_SPP=N.
#pragma once

#include <chrono>
#include <string>
#include <vector>

#include "cluster.h"
#include "raylane/core/error.h"
#include "raylane/render/film/film.h"
#include "render_request.h"

namespace raylane::cli {

struct RenderRequest;

// "1,4,16": pass counts in [1, max_spp], separated by commas; sorted, repeats dropped.
Result<std::vector<int>> parse_save_at(const std::string& list, int max_spp);

// --save-at: sets r.save_at (render_command.cpp's option table).
Status set_save_at(RenderRequest& r, const std::string& list);
// After every option is read: a listed count beyond --spp is never reached.
Status check_save_at(const RenderRequest& r);

// The course's names (Image_Pass_N.hdr): an output whose file name holds the placeholder
// {pass} is a pattern, and every image written from it, the series' and the final one, gets
// its pass count there (-o Image_Pass_{pass}.hdr --save-at 1,8 --spp 64 writes
// Image_Pass_1.hdr, Image_Pass_8.hdr and Image_Pass_64.hdr). README.md, "--save-at".
inline constexpr std::string_view kPassPlaceholder = "{pass}";
bool is_pass_pattern(const std::string& output);
// The output with each {pass} replaced by `passes`; any other output unchanged.
std::string with_passes(const std::string& output, int passes);
// After every option is read: braces in an output name are {pass} and nothing else, in the
// file name (not a folder), and only in a path render (a ray-casting view has no passes).
Status check_pass_patterns(const RenderRequest& r);
// The files the render's outputs are written as once the film holds `passes`: patterns filled
// in, except a pattern whose image the series already wrote at that count (the same file, bit
// for bit); other outputs as given.
std::vector<std::string> final_outputs(const RenderRequest& r, int passes);

// The series' image after `passes` for one output: a pattern filled in, else STEM.N.EXT in the
// folder of `output` (room.hdr → room.16.hdr).
std::string series_path(const std::string& output, int passes);

// Every file the series writes (colour outputs and their --aov siblings), for the checks made
// before rendering (outputs apart from inputs, folders writable).
std::vector<std::string> series_outputs(const RenderRequest& r);

// Writes the series as the render goes. after_pass() is called by every process of an MPI job
// after the same passes (it assembles the film, a collective step); rank 0 writes.
class PassSeries {
 public:
  PassSeries(const RenderRequest& r, const Cluster& cluster) : r_(r), cluster_(cluster) {}

  // A --resume film already holds `passes`: a listed count equal to it is written now, the
  // smaller ones cannot be any more (a warning names them).
  void start(const Film& film);
  void after_pass(int done, const Film& film);
  // After the render: the listed counts it stopped before (--time, Ctrl-C), in a warning.
  void finish(int passes_done) const;
  bool failed() const { return failed_; }
  // What was written, for --stats-json (rank 0).
  const std::vector<SeriesSave>& saves() const { return saves_; }

 private:
  void write(const Film& film, int passes);

  const RenderRequest& r_;
  const Cluster& cluster_;
  bool failed_ = false;
  std::vector<SeriesSave> saves_;
  // The clocks, and how much of them the writing of the series took (left out of each save's
  // cost: a render stopped at N spp does not write the images before N).
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double writing_seconds_ = 0, writing_cpu_ = 0;
};

// Writes a path render's `colour` outputs and their --aov siblings from the film, one image at
// a time: the colour image once, each AOV's image and an EXR's layers only while its file is
// written. Writing then needs little beside the film (render_memory.cpp counts it), where
// making every image first held them all at once. Returns the paths written (rescue files
// where they replaced an output); `failed` as write_render_output sets it.
std::vector<std::string> write_film_outputs(const std::vector<std::string>& colour,
                                            const Film& film, const WriteOptions& options,
                                            bool& failed);

// This process's CPU time so far, user and system, all threads (getrusage).
double process_cpu_seconds();

}  // namespace raylane::cli
