#include "kerf/solve/cholmod_ordering.hpp"

namespace kerf {

bool is_cholmod_ordering(const std::string& name) {
  return name == "nested-dissection" || name == "metis" || name == "amd" || name == "cholmod";
}

} // namespace kerf
