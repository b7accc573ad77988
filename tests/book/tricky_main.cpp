/* ---------------------------------------------------------------------------------------------
 * Tricky chapter: a test input for the literate filter.
 *
 * Sample runs:  ./99_tricky --scene beam.json   # prints <nothing> @all \endcode
 *
 *     +-------+   fixed at x = 0, loaded at x = L
 *     |  #V   |
 *     +-------+
 * --------------------------------------------------------------------------------------------- */

// # Including the headers
//
// We need `std::vector<double>` here, and std::vector<double> outside a code span too.
// The mesh has #V by 3 positions; @param is not a command here, 50% and %s are text,
// a\b is a path, \alpha without a formula prints as it is, and <foo> is no tag, while
// <b>bold</b> is. Formulas keep everything: \f$ \#V \times 3,\ a < b,\ \%x \f$ and
// \f[
//   \mathbf{K} \mathbf{u} = \mathbf{f}, \quad \sum_{e} \int_{\Omega_e} B^T C B \, dx
// \f]
// and a link to \ref chapter_99 "the chapter" and [a web page](https://example.org/a#b%20c).
// -----------------------------------------------------------------------------------------
// ## A subsection {#tricky_subsection}
#include <vector>
#include <string> // trailing comments stay in the code: #V @x \endcode

// A fenced block in prose, and an indented one:
// ```
// ./99_tricky --scene <file>.json   # @ and # are fine in here
// ```
//
//     int indented = 1 << 3; // #V
//
// - a list item with \f$ x_i \f$
//     continued with #V.

int main() {
  // Comments inside functions split the code, as in deal.II.
  std::string s = R"(```)";

  return static_cast<int>(s.size()) - 3;
}
