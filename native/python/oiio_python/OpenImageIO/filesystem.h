// See imageio.h: the Python-backed stand-in for OpenImageIO's C++ API.
#pragma once
#include "imageio.h"
