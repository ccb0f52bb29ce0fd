#include "stats_json.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "raylane/core/atomic_file.h"
#include "raylane/core/strings.h"
#include "raylane/render/raycast.h"

namespace raylane::cli {

namespace {

// The length of the well-formed UTF-8 sequence at s[i] (RFC 3629, section 4: no overlong
// forms, no surrogates, nothing above U+10FFFF), or 0 if the bytes there are not one.
std::size_t utf8_length(std::string_view s, std::size_t i) {
  auto byte = [&](std::size_t k) { return k < s.size() ? static_cast<unsigned char>(s[k]) : 0u; };
  auto tail = [&](std::size_t k, unsigned lo = 0x80, unsigned hi = 0xBF) {
    return byte(k) >= lo && byte(k) <= hi;
  };
  const unsigned b = byte(i);
  if (b < 0x80) return 1;
  if (b >= 0xC2 && b <= 0xDF) return tail(i + 1) ? 2 : 0;
  if (b >= 0xE0 && b <= 0xEF) {
    const unsigned lo = b == 0xE0 ? 0xA0 : 0x80, hi = b == 0xED ? 0x9F : 0xBF;
    return tail(i + 1, lo, hi) && tail(i + 2) ? 3 : 0;
  }
  if (b >= 0xF0 && b <= 0xF4) {
    const unsigned lo = b == 0xF0 ? 0x90 : 0x80, hi = b == 0xF4 ? 0x8F : 0xBF;
    return tail(i + 1, lo, hi) && tail(i + 2) && tail(i + 3) ? 4 : 0;
  }
  return 0;
}

// A JSON string: quotes, backslashes and control bytes escaped (RFC 8259, section 7). JSON text
// is UTF-8 (section 8.1), and a file name may be any bytes: each byte that starts no
// well-formed sequence becomes U+FFFD, as a lossy UTF-8 decoder does, so the file stays JSON.
std::string json_string(std::string_view s) {
  std::string out = "\"";
  for (std::size_t i = 0; i < s.size();) {
    const char c = s[i];
    const auto u = static_cast<unsigned char>(c);
    const std::size_t n = utf8_length(s, i);
    if (n == 0) {
      out += "\\ufffd";
      ++i;
      continue;
    }
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (u < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", u);
      out += buf;
    } else {
      out.append(s.substr(i, n));
    }
    i += n;
  }
  return out + "\"";
}

// A JSON number: 17 significant digits (a double read back is the same double); JSON has no
// NaN or infinity, so those are null.
std::string json_number(double v) {
  if (!std::isfinite(v)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// Builds `{"key": value, ...}` one member at a time.
class JsonObject {
 public:
  JsonObject& raw(std::string_view key, const std::string& value) {
    text_ += cat(text_.empty() ? "{" : ", ", json_string(key), ": ", value);
    return *this;
  }
  JsonObject& number(std::string_view key, double v) { return raw(key, json_number(v)); }
  JsonObject& count(std::string_view key, uint64_t v) { return raw(key, std::to_string(v)); }
  JsonObject& string(std::string_view key, std::string_view v) { return raw(key, json_string(v)); }
  JsonObject& boolean(std::string_view key, bool v) { return raw(key, v ? "true" : "false"); }
  std::string str() const { return text_.empty() ? "{}" : text_ + "}"; }

 private:
  std::string text_;
};

std::string phases_json(const RenderSummary& s) {
  const PathPhases& p = s.stats.phases;
  double available = s.seconds * s.threads * s.processes;
  return JsonObject()
      .number("camera_rays", p.camera)
      .number("tracing_camera_rays", p.trace_camera)
      .number("tracing_bounce_and_shadow_rays", p.trace_rest)
      .number("shading", p.shade)
      .number("light_sampling", p.lights)
      .number("film", p.film)
      .number("idle_and_other", std::max(0.0, available - p.total()))
      .number("thread_seconds", available)
      .str();
}

std::string string_array(const std::vector<std::string>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i)
    out += cat(i ? ", " : "", json_string(v[i]));
  return out + "]";
}

// [{"spp": N, "seconds": ..., "cpu_seconds": ..., "outputs": [...]}, ...]
std::string series_json(const std::vector<SeriesSave>& series) {
  std::string out = "[";
  for (std::size_t i = 0; i < series.size(); ++i)
    out += cat(i ? ", " : "", JsonObject()
                                  .count("spp", uint64_t(series[i].spp))
                                  .number("seconds", series[i].seconds)
                                  .number("cpu_seconds", series[i].cpu_seconds)
                                  .raw("outputs", string_array(series[i].outputs))
                                  .str());
  return out + "]";
}

}  // namespace

std::string summary_json(const RenderSummary& s) {
  const PathStats& st = s.stats;
  JsonObject o;
  o.count("width", s.width).count("height", s.height);
  if (!s.region.empty()) o.raw("region", s.region);
  o.string("mode", s.mode);
  if (s.mode == "path")
    o.string("integrator", s.integrator).string("sampler", s.sampler).string("shading", s.shading);
  o.count("spp", uint64_t(s.spp))
      .boolean("interrupted", s.interrupted)
      .number("seconds", s.seconds);
  o.raw("rays", JsonObject()
                    .count("camera", st.camera_rays)
                    .count("bounce", st.bounce_rays)
                    .count("shadow", st.shadow_rays)
                    .count("total", st.rays())
                    .str());
  o.number("mrays_per_second", s.seconds > 0 ? double(st.rays()) / s.seconds * 1e-6 : 0.0);
  if (s.mode == "path") o.count("nonfinite_samples", st.nonfinite_samples);
  o.raw("phases", s.phases_timed ? phases_json(s) : "null");
  o.string("tracer", s.tracer).string("isa", s.isa);
  o.count("threads", uint64_t(s.threads)).count("processes", uint64_t(s.processes));
  o.raw("bvh",
        JsonObject().count("nodes", s.bvh_nodes).number("build_seconds", s.bvh_seconds).str());
  if (s.processes > 1)
    o.raw("balance", JsonObject()
                         .number("wait_seconds", s.wait_seconds)
                         .number("busy_seconds", s.busy_seconds)
                         .count("tiles_moved", uint64_t(s.tiles_moved))
                         .count("balances", uint64_t(s.balances))
                         .str());
  if (s.path) o.raw("series", series_json(s.series));
  o.raw("outputs", string_array(s.outputs));
  return o.str() + "\n";
}

bool write_summary_json(const std::string& path, const RenderSummary& s) {
  Status written = write_file_atomically(path, summary_json(s));
  if (!written)
    std::fprintf(stderr, "raylane: cannot write %s: %s\n", path.c_str(), written.error().c_str());
  return written.ok();
}

RenderSummary render_summary(const RenderRequest& r, const Scene& scene, const Bvh& bvh,
                             const PathStats& stats, const PathOutcome& run, double seconds,
                             bool interrupted, int processes, std::vector<std::string> written) {
  RenderSummary s;
  s.width = scene.width, s.height = scene.height;
  if (const auto& g = r.path_settings.region)
    s.region = cat("[", g->x0, ", ", g->y0, ", ", g->x1, ", ", g->y1, "]");
  s.mode = r.path ? "path" : std::string(raycast_mode_name(r.mode));
  if (r.path) {
    const PathSettings& p = r.path_settings;
    s.integrator = integrator_name(p.integrator);
    s.sampler = sampler_name(p.sampler);
    s.shading = shading_name(p.shading);
  }
  s.spp = r.path ? stats.passes : 1;
  s.interrupted = interrupted;
  s.seconds = seconds;
  s.stats = stats;
  s.phases_timed = r.path && r.path_settings.time_phases;
  s.tracer = tracer_backend_name(r.tracer);
  s.isa = isa_name(r.isa);
  s.threads = omp_get_max_threads();
  s.processes = processes;
  s.bvh_nodes = bvh.nodes.size();
  s.bvh_seconds = bvh.stats.build_seconds;
  s.wait_seconds = run.wait_seconds, s.busy_seconds = run.busy_seconds;
  s.tiles_moved = run.tiles_moved, s.balances = run.balances;
  s.path = r.path;
  s.series = run.series;
  s.outputs = std::move(written);
  return s;
}

}  // namespace raylane::cli
