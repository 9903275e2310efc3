#pragma once
// gnuplot as a child process, for every figure the tool draws (the commands' plots and the
// validation reports' figures). Scripts are handed over as text; the caller's script names its
// output files (usually an AtomicFile's temporary) and checks them afterwards.
#include <string>

namespace allanlab {

// Whether an executable gnuplot is on PATH; if not, *why says how to install it.
bool FindGnuplot(std::string* why);

// `text` as a gnuplot single-quoted string (everything literal; a quote doubled).
std::string GnuplotQuoted(const std::string& text);

// Runs gnuplot on `script` (standard input /dev/null, standard output discarded) and waits for it.
// On failure *why is one line: gnuplot missing (with the install hint), or its first error line.
bool RunGnuplot(const std::string& script, std::string* why);

// Whether gnuplot wrote a non-empty image at `path`; if not, *why says so.
bool GnuplotWroteImage(const std::string& path, std::string* why);

}  // namespace allanlab
