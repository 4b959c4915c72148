#pragma once
#include <string>

namespace semantic_edge_vo {
namespace synthetic {

/// The three scene types of the paper's Table I.
enum class SceneType { kCity, kVillage, kHighway };

inline const char* toString(SceneType type) {
  switch (type) {
    case SceneType::kCity: return "city";
    case SceneType::kVillage: return "village";
    case SceneType::kHighway: return "highway";
  }
  return "unknown";
}

/// Parses "city", "village" or "highway"; false (and `type` unchanged) otherwise.
inline bool parseSceneType(const std::string& text, SceneType* type) {
  for (SceneType t : {SceneType::kCity, SceneType::kVillage, SceneType::kHighway})
    if (text == toString(t)) {
      *type = t;
      return true;
    }
  return false;
}

}  // namespace synthetic
}  // namespace semantic_edge_vo
