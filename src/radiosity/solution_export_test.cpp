#include "radiosity/solution_export.h"
