// Stands in for OpenCV's umbrella header, which includes every module Debian built (calib3d, dnn, ...): MobileAR's
// samplers use core and imgproc alone, and these are all bench_peers.sh installs.
#pragma once
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/imgproc/types_c.h>
