#pragma once
// QApplication sets the C library's locale from the user's environment (LANG, LC_ALL). In a decimal-comma
// locale (de_DE, fr_FR, ...) printf would write "1,5" and strtod/atof stop at the '.' of "1.5". ReamSim's own
// readers and writers do not depend on it (from_chars, to_chars), but the libraries it calls may (VTK's text
// formats and the like). Numbers in files are not locale text: call this right after constructing
// QApplication, as Qt's documentation advises. Qt's own number display follows QLocale and is not affected.
#include <clocale>

namespace reamsim::ui {

inline void useCNumberFormats() { std::setlocale(LC_NUMERIC, "C"); }

}  // namespace reamsim::ui
