#pragma once

#include <string>

#include "camera/film.h"

namespace candela {

// Reads a PFM (colour "PF" or grey "Pf", either byte order). Throws std::runtime_error.
Film read_pfm(const std::string& path);

}  // namespace candela
