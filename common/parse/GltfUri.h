// The URIs a glTF names its buffers and images by: "data:" URIs with base64 payloads (decoded
// here) and relative file references (percent-decoded here, read by the caller's file reader).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace prism {

struct DataUri {
  std::string mediaType;     // "application/octet-stream", "image/png", ...
  std::string_view payload;  // base64 text, a view into the URI
};

// The parts of a "data:[type][;base64],payload" URI; nothing when uri is not a data URI.
// Throws std::invalid_argument for a data URI that is not base64.
std::optional<DataUri> splitDataUri(std::string_view uri);

// Bytes a base64 text decodes to (padding and length checked by decodeBase64).
uint64_t base64DecodedSize(std::string_view text);

// Decodes standard base64 (RFC 4648, '=' padding optional). Throws std::invalid_argument naming
// the first character that is not base64 and its offset.
std::vector<uint8_t> decodeBase64(std::string_view text);

// A relative URI reference as a path: "%20" and the like decoded. Throws std::invalid_argument
// for URIs with a scheme (http:, file:, ...) or an absolute path.
std::string uriToRelativePath(std::string_view uri);

}  // namespace prism
