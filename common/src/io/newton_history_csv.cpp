#include "kerf/io/newton_history_csv.hpp"

#include "kerf/app/input_error.hpp"

#include <cstdio>

namespace kerf {

void write_newton_history_csv(const std::filesystem::path& file, const std::vector<NewtonIteration>& history) {
  std::FILE* out = std::fopen(file.string().c_str(), "w");
  if (!out) throw InputError(file.string(), "file", "cannot write the convergence history");
  std::fprintf(out, "step,iteration,relative_residual,warped_fallback\n");
  for (const NewtonIteration& it : history)
    std::fprintf(out, "%d,%d,%.6e,%d\n", it.step, it.iteration, it.relative_residual, it.warped_fallback ? 1 : 0);
  std::fclose(out);
}

} // namespace kerf
