// The CalculiX executable the validation tests run.
#pragma once

#include <doctest/doctest.h>

#include <string>

namespace support {

/// The ccx found at configure time (KERF_CCX); the validation is mandatory, so a missing ccx
/// fails the calling test instead of skipping it.
inline std::string ccx_path() {
  const std::string ccx = KERF_CCX;
  if (ccx.empty() || ccx.find("NOTFOUND") != std::string::npos)
    FAIL("calculix-ccx is required for the validation tests (./kerf.sh installs it); reconfigure after installing");
  return ccx;
}

} // namespace support
