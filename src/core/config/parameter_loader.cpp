#include "semantic_edge_vo/config/parameter_loader.h"

namespace semantic_edge_vo {

std::string ParameterLoader::unknownNames() const {
  std::string unknown;
  for (const std::string& name : source_.names())
    if (!read_.count(name)) unknown += (unknown.empty() ? "" : ", ") + source_.resolve(name);
  return unknown;
}

}  // namespace semantic_edge_vo
