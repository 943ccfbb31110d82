// What made this ssrt: its version, the git commit it was built from and the compiler, for
// `ssrt --version` and the references `ssrt check --update` writes.
#pragma once

#include <map>
#include <string>

namespace ssrt::cli {

// "ssrt 0.1.0 (commit 9215045..., gcc 12.2.0)": what `ssrt --version` prints.
std::string versionLine();

// A version line read back into ssrt:version, ssrt:commit and ssrt:compiler (empty when the
// line is not one).
std::map<std::string, std::string> parseVersionLine(const std::string& line);

}  // namespace ssrt::cli
