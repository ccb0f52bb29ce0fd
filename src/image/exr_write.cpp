// Writing EXR files (OpenEXR's C++ library: our own data, so its exceptions are the only
// errors). Reading is in exr.cpp.
#include <Imath/half.h>
#include <OpenEXR/Iex.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <exception>

#include "raylane/core/strings.h"
#include "raylane/image/exr.h"

namespace raylane {

namespace {

// Imf::OStream over the temporary file. OpenEXR reports a failed write by an exception, but
// OutputFile's destructor, which writes the line offset table, swallows them: the stream
// remembers that it failed.
class FileStream : public Imf::OStream {
 public:
  explicit FileStream(std::FILE* f) : Imf::OStream("the EXR output"), f_(f) {}
  void write(const char c[], int n) override {
    if (std::fwrite(c, 1, std::size_t(n), f_) != std::size_t(n)) fail("write failed");
  }
  uint64_t tellp() override { return uint64_t(::ftello(f_)); }
  void seekp(uint64_t pos) override {
    if (::fseeko(f_, off_t(pos), SEEK_SET) != 0) fail("seek failed");
  }
  bool failed() const { return failed_; }

 private:
  [[noreturn]] void fail(const char* what) {
    failed_ = true;
    throw Iex::IoExc(cat(what, ": ", std::strerror(errno)));
  }
  std::FILE* f_;
  bool failed_ = false;
};

Status check_layer(const Image& image, const ExrLayer& layer) {
  // Nested layers ("diffuse.direct") are names with dots between non-empty parts.
  const std::string& n = layer.name;
  if (n.empty() || n.front() == '.' || n.back() == '.' || n.find("..") != std::string::npos)
    return Error{cat("bad EXR layer name ", in_quotes(n), " (not empty, no empty part)")};
  if (layer.channels.empty()) return Error{cat("EXR layer ", layer.name, " has no channels")};
  for (const auto& c : layer.channels)
    if (c.empty() || c.find('.') != std::string::npos)
      return Error{cat("bad EXR channel name ", in_quotes(c), " in layer ", layer.name)};
  if (layer.data.size() != std::size_t(image.width) * image.height * layer.channels.size())
    return Error{cat("EXR layer ", layer.name, " holds ", layer.data.size(), " values, not ",
                     image.width, "x", image.height, "x", layer.channels.size())};
  return ok_status();
}

// KEY=value lines as string attributes; a key the format itself defines ("channels",
// "dataWindow", …) would change what the file means, so it is refused.
Status add_metadata(Imf::Header& header, const std::vector<std::string>& metadata) {
  for (const std::string& line : metadata) {
    std::size_t eq = line.find('=');
    if (eq == 0 || eq == std::string::npos)
      return Error{cat("metadata ", in_quotes(line), " is not KEY=value")};
    std::string key = line.substr(0, eq);
    if (header.find(key) != header.end())
      return Error{cat("metadata key ", in_quotes(key), " is an EXR attribute already")};
    header.insert(key, Imf::StringAttribute(line.substr(eq + 1)));
  }
  return ok_status();
}

// Interleaved samples of one type, as the frame buffer points into them: OpenEXR writes a
// channel only from a slice of the channel's own type.
struct Samples {
  const char* base;
  std::size_t bytes;  // per sample
  Imf::PixelType type;
};

void add_channel(Imf::Header& header, Imf::FrameBuffer& fb, const std::string& name,
                 const Samples& s, std::size_t k, std::size_t stride, uint32_t width) {
  header.channels().insert(name, Imf::Channel(s.type));
  char* first = const_cast<char*>(s.base + k * s.bytes);
  fb.insert(name, Imf::Slice(s.type, first, stride * s.bytes, stride * width * s.bytes));
}

// Half's largest finite value: a larger one would be stored as infinity, which every
// reader of textures refuses.
constexpr float kHalfMax = 65504.0f;

// Round to nearest (Imath's float-to-half conversion), after clamping; NaN stays NaN.
std::vector<Imath::half> to_half(const std::vector<float>& v) {
  std::vector<Imath::half> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    out[i] = Imath::half(std::clamp(v[i], -kHalfMax, kHalfMax));
  return out;
}

Status write_exr_unguarded(std::FILE* f, const Image& image, const std::vector<ExrLayer>& layers,
                           const ExrWriteOptions& options) {
  Imf::Header header(int(image.width), int(image.height));
  header.compression() = Imf::ZIP_COMPRESSION;
  header.insert("software", Imf::StringAttribute(cat("raylane ", RAYLANE_VERSION)));
  if (Status s = add_metadata(header, options.metadata); !s) return s;
  // Half samples are converted into copies that live until the pixels are written.
  std::vector<std::vector<Imath::half>> halves;
  halves.reserve(layers.size() + 1);
  auto source = [&](const std::vector<float>& v) -> Samples {
    if (!options.half) return {reinterpret_cast<const char*>(v.data()), sizeof(float), Imf::FLOAT};
    halves.push_back(to_half(v));
    return {reinterpret_cast<const char*>(halves.back().data()), sizeof(Imath::half), Imf::HALF};
  };
  Imf::FrameBuffer fb;
  const Samples rgb = source(image.rgb);
  for (std::size_t k = 0; k < 3; ++k)
    add_channel(header, fb, std::string(1, "RGB"[k]), rgb, k, 3, image.width);
  for (const ExrLayer& layer : layers) {
    if (Status s = check_layer(image, layer); !s) return s;
    const Samples data = source(layer.data);
    const std::size_t n = layer.channels.size();
    for (std::size_t k = 0; k < n; ++k) {
      std::string name = cat(layer.name, ".", layer.channels[k]);
      if (header.channels().findChannel(name))
        return Error{cat("EXR channel ", name, " is given twice")};
      add_channel(header, fb, name, data, k, n, image.width);
    }
  }
  FileStream stream(f);
  {
    Imf::OutputFile out(stream, header);
    out.setFrameBuffer(fb);
    out.writePixels(int(image.height));
  }  // the destructor writes the line offset table
  if (stream.failed()) return Error{cat("write failed: ", std::strerror(errno))};
  return ok_status();
}

}  // namespace

Status write_exr(std::FILE* f, const Image& image, const std::vector<ExrLayer>& layers,
                 const ExrWriteOptions& options) {
  if (image.width == 0 || image.height == 0) return Error{"cannot write an empty EXR image"};
  try {
    return write_exr_unguarded(f, image, layers, options);
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    return Error{cat("EXR write failed: ", e.what())};
  }
}

}  // namespace raylane
