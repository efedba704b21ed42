// IES LM-63 photometric files: a luminaire's luminous intensity distribution
// as the lighting industry publishes it, read in the 1986 (no first line), 1991 ("IESNA91"),
// 1995 ("IESNA:LM-63-1995") and 2002 ("IESNA:LM-63-2002") formats.
//
// The file (ANSI/IESNA LM-63-02 §5): keyword lines "[KEYWORD] text" (kept), then "TILT=NONE",
// "TILT=INCLUDE" (followed by the lamp-to-luminaire geometry, the number of tilt angles, the
// angles and their multiplying factors) or "TILT=<file>"; then, as numbers separated by blanks,
// commas or line ends: number of lamps, lumens per lamp (-1: absolute photometry), candela
// multiplier, number of vertical angles, number of horizontal angles, photometric type
// (1 = C, 2 = B, 3 = A), units (1 feet, 2 metres), width, length, height of the luminous opening,
// ballast factor, a reserved number (the 1986 "ballast-lamp factor"), input watts, the vertical
// angles, the horizontal angles and the candela values, the vertical angles' values for each
// horizontal angle in turn.
//
// Tilt data are read and not applied: they describe how the lamp's output changes when the
// luminaire is tilted from the position it was measured in, which Candela's lights do not model
// (Radiance's ies2rad applies them only with -t); TILT=<file> names a file that is not read.
//
// The table's symmetry and interpolation are Photometry's (io/photometry.h).
//
// Errors: InputError naming the file, the line and the column (the number that is wrong and what
// was expected), for a missing TILT line, a non-number, a count out of range or more values than
// the file holds (checked before anything is allocated), angles out of range or not increasing, a
// negative or non-finite candela value, a multiplier or ballast factor not > 0.
#pragma once

#include <string>
#include <string_view>

#include "io/photometry.h"
#include "util/error.h"

namespace candela {

// `text` is the file's contents and `file` its name for messages.
Photometry parse_ies(std::string_view text, const std::string& file);
// Reads path (at most 16 MiB: the largest published files are well under 1 MiB).
Photometry read_ies(const std::string& path);

}  // namespace candela
