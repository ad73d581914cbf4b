#include "parse/GltfUri.h"

#include <array>
#include <stdexcept>

namespace prism {

namespace {

constexpr uint8_t kNotBase64 = 0xff;

constexpr std::array<uint8_t, 256> base64Table() {
  std::array<uint8_t, 256> table{};
  for (uint8_t& v : table) v = kNotBase64;
  constexpr std::string_view kAlphabet =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  for (size_t i = 0; i < kAlphabet.size(); ++i) {
    table[static_cast<uint8_t>(kAlphabet[i])] = static_cast<uint8_t>(i);
  }
  return table;
}

constexpr std::array<uint8_t, 256> kBase64 = base64Table();

std::string_view withoutPadding(std::string_view text) {
  while (!text.empty() && text.back() == '=') text.remove_suffix(1);
  return text;
}

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::optional<DataUri> splitDataUri(std::string_view uri) {
  if (!uri.starts_with("data:")) return std::nullopt;
  const size_t comma = uri.find(',');
  if (comma == std::string_view::npos) throw std::invalid_argument("a data URI without ','");
  std::string_view header = uri.substr(5, comma - 5);
  if (!header.ends_with(";base64")) {
    throw std::invalid_argument("a data URI that is not base64 (';base64' is missing)");
  }
  header.remove_suffix(7);
  return DataUri{std::string(header), uri.substr(comma + 1)};
}

uint64_t base64DecodedSize(std::string_view text) {
  const uint64_t n = withoutPadding(text).size();
  return n / 4 * 3 + (n % 4 == 0 ? 0 : n % 4 - 1);
}

std::vector<uint8_t> decodeBase64(std::string_view text) {
  const std::string_view body = withoutPadding(text);
  if (body.size() % 4 == 1) throw std::invalid_argument("base64 text of an impossible length");
  std::vector<uint8_t> out(base64DecodedSize(text));
  const auto* in = reinterpret_cast<const uint8_t*>(body.data());
  const size_t whole = body.size() / 4;
  uint8_t* o = out.data();
  auto fail = [&](size_t at) -> void {
    throw std::invalid_argument("'" + std::string(1, body[at]) + "' at character " +
                                std::to_string(at) + " is not base64");
  };
  for (size_t q = 0; q < whole; ++q, in += 4, o += 3) {
    const uint8_t a = kBase64[in[0]], b = kBase64[in[1]], c = kBase64[in[2]], d = kBase64[in[3]];
    if ((a | b | c | d) & 0x80) {  // kNotBase64 has the top bit; the alphabet does not
      for (size_t k = 0; k < 4; ++k) {
        if (kBase64[in[k]] == kNotBase64) fail(4 * q + k);
      }
    }
    const uint32_t v = uint32_t{a} << 18 | uint32_t{b} << 12 | uint32_t{c} << 6 | d;
    o[0] = static_cast<uint8_t>(v >> 16);
    o[1] = static_cast<uint8_t>(v >> 8);
    o[2] = static_cast<uint8_t>(v);
  }
  const size_t rest = body.size() % 4;
  if (rest > 0) {
    uint32_t v = 0;
    for (size_t k = 0; k < rest; ++k) {
      const uint8_t x = kBase64[in[k]];
      if (x == kNotBase64) fail(4 * whole + k);
      v |= uint32_t{x} << (18 - 6 * k);
    }
    o[0] = static_cast<uint8_t>(v >> 16);
    if (rest == 3) o[1] = static_cast<uint8_t>(v >> 8);
  }
  return out;
}

std::string uriToRelativePath(std::string_view uri) {
  const size_t colon = uri.find(':');
  const size_t slash = uri.find('/');
  if (colon != std::string_view::npos && (slash == std::string_view::npos || colon < slash)) {
    throw std::invalid_argument("'" + std::string(uri) +
                                "' is not a file beside the glTF (Prism reads relative paths and "
                                "data: URIs only)");
  }
  if (uri.starts_with('/')) {
    throw std::invalid_argument("'" + std::string(uri) +
                                "' is an absolute path (glTF URIs are "
                                "relative to the file)");
  }
  std::string path;
  path.reserve(uri.size());
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hexValue(uri[i + 1]) >= 0 &&
        hexValue(uri[i + 2]) >= 0) {
      path += static_cast<char>(hexValue(uri[i + 1]) * 16 + hexValue(uri[i + 2]));
      i += 2;
    } else {
      path += uri[i];
    }
  }
  return path;
}

}  // namespace prism
