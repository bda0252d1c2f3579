#pragma once
// `lcprelax learn scene --init-from RESULT.json` (docs/cli.md): the initial values of a run
// taken from the "learned" map of an earlier run's --json output. Every parameter this run
// learns must be there (its initial value); an entry for a parameter this run holds fixed
// sets that fixed value (so that a run can continue an earlier one on a subset of its
// parameters, block by block); an entry naming no parameter is an error. Values are in the
// parameters' own units (SI: kg, kg·m², m, rad; μ dimensionless), as the JSON prints them.
#include <lcprelax/learn/parameters.hpp>

#include <string>

namespace lcprelax::cli {

/// Sets θ's values from `path` (rules above). Throws InputError naming --init-from, the file
/// and the entry: unreadable file, not JSON, no "learned" object, a learned parameter
/// missing, a value that is not a finite number, an entry naming no parameter.
void set_initial_values_from(const std::string& path, learn::ParameterSet& theta);

}  // namespace lcprelax::cli
