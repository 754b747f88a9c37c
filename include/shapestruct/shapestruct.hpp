// SPDX-License-Identifier: MIT
// Thin umbrella: configuration, core vocabulary and concepts. Stage headers (geometry/, io/, ...) are opt-in.
#pragma once

#include <Eigen/Core>

#include "shapestruct/config.hpp"
#include "shapestruct/core/concepts.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/core/status.hpp"
#include "shapestruct/core/traits.hpp"
#include "shapestruct/core/types.hpp"
