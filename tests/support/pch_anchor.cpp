// SPDX-License-Identifier: MIT
// Empty translation unit that owns the tests' precompiled header (see tests/CMakeLists.txt).
