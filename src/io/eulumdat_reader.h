// EULUMDAT (.ldt) photometric files, the European luminaire format: one value
// per line —
//    1 company, 2 Ityp (type indicator), 3 Isym (symmetry 0–4), 4 Mc (C-planes in 360°), 5 Dc,
//    6 Ng (intensities per plane), 7 Dg, 8 measurement report, 9 luminaire name, 10 luminaire
//    number, 11 file name, 12 date/user, 13–15 luminaire length, width, height (mm), 16–17
//    luminous area length and width (mm), 18–21 luminous area heights at C0, C90, C180, C270,
//    22 downward flux fraction (%), 23 light output ratio (%), 24 intensity conversion factor,
//    25 tilt during measurement, 26 n (lamp sets), then per set: 26a number of lamps, 26b type,
//    26c total luminous flux (lm), 26d colour, 26e colour rendering, 26f wattage (W); 27 ten
//    direct ratios; the Mc C-angles; the Ng γ-angles; the intensities in cd per 1000 lamp lumens,
//    Ng per C-plane, for the planes the symmetry keeps: Isym 0 all Mc; 1 one (rotational);
//    2 C0 to C180 (Mc/2 + 1); 3 C90 to C270 (Mc/2 + 1); 4 C0 to C90 (Mc/4 + 1).
// The intensities become candela: × the first lamp set's flux / 1000 × the conversion factor.
// The result is a type C Photometry (io/photometry.h) whose horizontal angles are the stored
// planes, so its symmetry is the file's.
//
// Errors: InputError naming the file and line and what was expected, for a missing line, a
// non-number, a count out of range or one the file cannot hold (checked before allocating), an
// Isym whose plane count does not divide, angles out of range or not increasing, a negative
// intensity, a lamp flux not > 0.
#pragma once

#include <string>
#include <string_view>

#include "io/photometry.h"
#include "util/error.h"

namespace candela {

// `text` is the file's contents and `file` its name for messages.
Photometry parse_eulumdat(std::string_view text, const std::string& file);
// Reads path (at most 16 MiB).
Photometry read_eulumdat(const std::string& path);

}  // namespace candela
