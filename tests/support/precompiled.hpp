// The headers nearly every test file parses, precompiled once for all tests
// (tests/CMakeLists.txt: dspdem_test_pch). Only third-party and standard headers: a change to
// dspdem's own headers rebuilds only the tests that include them.
#pragma once
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>
