#include "kerf/fem/positive_jacobian.hpp"

#include <sstream>
#include <stdexcept>

namespace kerf {

void throw_non_positive_jacobian(double det_J, const char* function, Eigen::Index element) {
  std::ostringstream message;
  message << function << ": ";
  if (element >= 0) message << "element " << element << ": ";
  message << "det J = " << det_J
          << " <= 0: the tet is inverted (its corners are not listed with det[x1-x0, x2-x0, x3-x0] > 0), "
             "flat, or folded by a misplaced mid-edge node; check_tet_mesh() reorients or refuses such tets";
  throw std::invalid_argument(message.str());
}

} // namespace kerf
