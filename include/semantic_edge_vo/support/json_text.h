#pragma once
#include <string>

namespace semantic_edge_vo {

/// `text` as a quoted JSON string, escaped per RFC 8259 (quote, backslash, control characters).
/// The reports write their JSON by hand: no JSON library is packaged.
std::string jsonString(const std::string& text);

}  // namespace semantic_edge_vo
