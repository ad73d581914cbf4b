#include "image/ExrFile.h"

#include <OpenEXR/openexr.h>

#include <cstring>
#include <ctime>
#include <stdexcept>

namespace prism {
namespace {

// OpenEXR hands its detailed messages to a callback on the thread that failed.
thread_local std::string lastMessage;

void onError(exr_const_context_t, exr_result_t, const char* message) {
  lastMessage = message ? message : "";
}

exr_context_initializer_t initializer(bool silent) {
  exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
  init.error_handler_fn = onError;
  // A file cut short is an error, not an image with holes.
  init.flags |= EXR_CONTEXT_FLAG_DISABLE_CHUNK_RECONSTRUCTION;
  if (silent) init.flags |= EXR_CONTEXT_FLAG_SILENT_HEADER_PARSE;
  return init;
}

[[noreturn]] void fail(exr_result_t result) {
  std::string message = lastMessage.empty() ? exr_get_default_error_message(result) : lastMessage;
  lastMessage.clear();
  throw std::runtime_error(message);
}

void check(exr_result_t result) {
  if (result != EXR_ERR_SUCCESS) fail(result);
}

// OpenEXR's names for the attributes OpenImageIO calls otherwise, so files read the same
// whichever library wrote them.
const char* exrName(const std::string& name) {
  if (name == "ImageDescription") return "comments";
  if (name == "DateTime") return "capDate";
  return name.c_str();
}

// Closes the context on every path out (exr_finish also deletes a half-written file).
class Context {
 public:
  Context() = default;
  ~Context() {
    if (ctx_) exr_finish(&ctx_);
  }
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  exr_context_t* operator&() { return &ctx_; }
  operator exr_context_t() const { return ctx_; }
  // Flushes the offset table and closes the file, reporting failure.
  void finish() {
    const exr_result_t result = exr_finish(&ctx_);
    ctx_ = nullptr;
    check(result);
  }

 private:
  exr_context_t ctx_ = nullptr;
};

// Which of R, G, B (0, 1, 2) a channel name is; -1 for any other.
int rgbIndex(const char* name) {
  if (std::strcmp(name, "R") == 0) return 0;
  if (std::strcmp(name, "G") == 0) return 1;
  if (std::strcmp(name, "B") == 0) return 2;
  return -1;
}

// Points every R, G, B channel of a chunk at its place in the interleaved float image; the
// other channels are skipped (a null pointer).
template <typename Pipeline>
void bindChannels(Pipeline& pipe, const exr_chunk_info_t& chunk, int width, uint8_t* rows) {
  for (int c = 0; c < pipe.channel_count; ++c) {
    exr_coding_channel_info_t& channel = pipe.channels[c];
    const int index = rgbIndex(channel.channel_name);
    channel.user_data_type = EXR_PIXEL_FLOAT;
    channel.user_bytes_per_element = sizeof(float);
    channel.user_pixel_stride = sizeof(Color);
    channel.user_line_stride = static_cast<int32_t>(sizeof(Color)) * width;
    uint8_t* at = index < 0 ? nullptr
                            : rows + (static_cast<size_t>(chunk.start_y) * width) * sizeof(Color) +
                                  index * sizeof(float);
    if constexpr (std::is_same_v<Pipeline, exr_encode_pipeline_t>) {
      channel.encode_from_ptr = at;
    } else {
      channel.decode_to_ptr = at;
    }
  }
}

// OpenEXR 3.1's zlib encoder (ZIP, ZIPS) stores the deflated bytes when they come out exactly as
// long as the raw chunk, and every reader then takes them for raw pixels: a row of garbage, seen
// here on a rendered frame (AcademySoftwareFoundation/openexr#2306, fixed in 3.4). The raw bytes
// are what the format wants in that case, so this wrapper around the library's compressor stores
// them.
struct GuardedCompressor {
  exr_result_t (*compress)(exr_encode_pipeline_t*) = nullptr;
};

exr_result_t compressStoringRawWhenNotSmaller(exr_encode_pipeline_t* pipe) {
  const auto* guard = static_cast<const GuardedCompressor*>(pipe->encoding_user_data);
  const exr_result_t result = guard->compress(pipe);
  if (result == EXR_ERR_SUCCESS && pipe->compressed_bytes == pipe->packed_bytes &&
      pipe->compressed_buffer != pipe->packed_buffer) {
    std::memcpy(pipe->compressed_buffer, pipe->packed_buffer, pipe->packed_bytes);
  }
  return result;
}

std::string captureDate() {
  const std::time_t now = std::time(nullptr);
  std::tm local{};
  localtime_r(&now, &local);
  char text[32];
  std::strftime(text, sizeof(text), "%Y:%m:%d %H:%M:%S", &local);
  return text;
}

}  // namespace

void writeExr(const std::string& path, const ImageRgb& image, const ImageMetadata& metadata,
              const ExrEncoding& encoding) {
  lastMessage.clear();
  const exr_context_initializer_t init = initializer(false);
  Context ctx;
  check(exr_start_write(&ctx, path.c_str(), EXR_WRITE_FILE_DIRECTLY, &init));
  int part = 0;
  check(exr_add_part(ctx, "", EXR_STORAGE_SCANLINE, &part));
  check(exr_initialize_required_attr_simple(ctx, part, image.width, image.height,
                                            static_cast<exr_compression_t>(encoding.compression)));
  check(exr_set_zip_compression_level(ctx, part, encoding.zipLevel));
  for (const char* name : {"R", "G", "B"}) {
    check(exr_add_channel(ctx, part, name, EXR_PIXEL_FLOAT, EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1));
  }
  check(exr_attr_set_string(ctx, part, "Software", "Prism"));
  check(exr_attr_set_string(ctx, part, "capDate", captureDate().c_str()));
  for (const auto& [name, value] : metadata) {
    check(exr_attr_set_string(ctx, part, exrName(name), value.c_str()));
  }
  check(exr_write_header(ctx));

  int32_t linesPerChunk = 1;
  check(exr_get_scanlines_per_chunk(ctx, part, &linesPerChunk));
  // The encoder only reads through these pointers.
  auto* pixels = reinterpret_cast<uint8_t*>(const_cast<Color*>(image.pixels.data()));
  exr_encode_pipeline_t pipe = EXR_ENCODE_PIPELINE_INITIALIZER;
  GuardedCompressor guard;
  exr_result_t result = EXR_ERR_SUCCESS;
  for (int y = 0; y < image.height && result == EXR_ERR_SUCCESS; y += linesPerChunk) {
    exr_chunk_info_t chunk;
    result = exr_write_scanline_chunk_info(ctx, part, y, &chunk);
    if (result != EXR_ERR_SUCCESS) break;
    const bool first = y == 0;
    result = first ? exr_encoding_initialize(ctx, part, &chunk, &pipe)
                   : exr_encoding_update(ctx, part, &chunk, &pipe);
    if (result != EXR_ERR_SUCCESS) break;
    bindChannels(pipe, chunk, image.width, pixels);
    if (first) {
      result = exr_encoding_choose_default_routines(ctx, part, &pipe);
      if (pipe.compress_fn) {
        guard.compress = pipe.compress_fn;
        pipe.encoding_user_data = &guard;
        pipe.compress_fn = compressStoringRawWhenNotSmaller;
      }
    }
    if (result == EXR_ERR_SUCCESS) result = exr_encoding_run(ctx, part, &pipe);
  }
  exr_encoding_destroy(ctx, &pipe);
  check(result);
  ctx.finish();
}

std::optional<ImageRgb> readExr(const std::string& path) {
  lastMessage.clear();
  const exr_context_initializer_t init = initializer(false);
  Context ctx;
  check(exr_start_read(&ctx, path.c_str(), &init));
  int parts = 0;
  exr_storage_t storage = EXR_STORAGE_LAST_TYPE;
  const exr_attr_chlist_t* channels = nullptr;
  check(exr_get_count(ctx, &parts));
  check(exr_get_storage(ctx, 0, &storage));
  check(exr_get_channels(ctx, 0, &channels));
  int rgb = 0;
  for (int c = 0; c < channels->num_channels; ++c) {
    const exr_attr_chlist_entry_t& entry = channels->entries[c];
    if (rgbIndex(entry.name.str) < 0) continue;
    // Subsampled channels, and 32-bit integers (which OpenImageIO normalises to [0, 1] and takes
    // as display-encoded), are OpenImageIO's to read.
    if (entry.x_sampling != 1 || entry.y_sampling != 1 || entry.pixel_type == EXR_PIXEL_UINT) {
      return std::nullopt;
    }
    ++rgb;
  }
  if (parts != 1 || storage != EXR_STORAGE_SCANLINE || rgb != 3) return std::nullopt;

  exr_attr_box2i_t window;
  check(exr_get_data_window(ctx, 0, &window));
  const int64_t width = int64_t(window.max.x) - window.min.x + 1;
  const int64_t height = int64_t(window.max.y) - window.min.y + 1;
  if (width <= 0 || height <= 0) throw std::runtime_error("it has no pixels");
  ImageRgb image(static_cast<int>(width), static_cast<int>(height));
  auto* pixels = reinterpret_cast<uint8_t*>(image.pixels.data());

  int32_t linesPerChunk = 1;
  check(exr_get_scanlines_per_chunk(ctx, 0, &linesPerChunk));
  exr_decode_pipeline_t pipe = EXR_DECODE_PIPELINE_INITIALIZER;
  exr_result_t result = EXR_ERR_SUCCESS;
  bool first = true;
  for (int64_t y = window.min.y; y <= window.max.y && result == EXR_ERR_SUCCESS;
       y += linesPerChunk) {
    exr_chunk_info_t chunk;
    result = exr_read_scanline_chunk_info(ctx, 0, static_cast<int>(y), &chunk);
    if (result != EXR_ERR_SUCCESS) break;
    result = first ? exr_decoding_initialize(ctx, 0, &chunk, &pipe)
                   : exr_decoding_update(ctx, 0, &chunk, &pipe);
    if (result != EXR_ERR_SUCCESS) break;
    // Rows relative to the data window's top.
    exr_chunk_info_t relative = chunk;
    relative.start_y -= window.min.y;
    bindChannels(pipe, relative, image.width, pixels);
    if (first) result = exr_decoding_choose_default_routines(ctx, 0, &pipe);
    if (result == EXR_ERR_SUCCESS) result = exr_decoding_run(ctx, 0, &pipe);
    first = false;
  }
  exr_decoding_destroy(ctx, &pipe);
  check(result);
  return image;
}

std::optional<std::string> readExrText(const std::string& path, const std::string& name) {
  const exr_context_initializer_t init = initializer(true);
  Context ctx;
  if (exr_start_read(&ctx, path.c_str(), &init) != EXR_ERR_SUCCESS) {
    lastMessage.clear();
    return std::nullopt;
  }
  int32_t length = 0;
  const char* value = nullptr;
  if (exr_attr_get_string(ctx, 0, exrName(name), &length, &value) != EXR_ERR_SUCCESS || !value) {
    lastMessage.clear();
    return std::nullopt;
  }
  return std::string(value, static_cast<size_t>(length));
}

}  // namespace prism
