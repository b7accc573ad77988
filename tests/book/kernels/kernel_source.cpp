// A library file for the kernel tests of the literate filter (book/literate.cpp): not compiled.
#include <cmath>

namespace demo {

int add_one(int x); // a declaration: not the definition

// The kernel the page shows, with the two comment lines right above it,
// and a body that ends at the first `}` at the start of a line.
int add_one(int x) {
  if (x > 0) {
    return x + 1;
  }
  return x + 1;
}

double twice(double x) { return 2.0 * x; }
}

int twice(int x) {
  return 2 * x;
}

/// A template: its parameter line and its documentation come with it.
template <typename T>
T square(const T& x) {
  return x * x;
}

} // namespace demo
