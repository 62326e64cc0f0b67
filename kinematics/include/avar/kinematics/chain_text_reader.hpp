#pragma once
// Reader for the plain-text DH chain format of the shared IK benchmark chains
// (shared/bench/ik-chains.txt):
//   chain <name> <dof>                     starts a chain; exactly <dof> joint rows follow
//   <a> <alpha> <d> <theta> <lower> <upper>  one revolute joint, standard (distal) DH
// Lengths in metres, angles in radians; '#' starts a comment; blank lines are ignored.
// Load time only: allocates and throws InputError naming file, line and column.

#include <istream>
#include <string>
#include <vector>

#include "avar/core/input_error.hpp"
#include "avar/kinematics/denavit_hartenberg.hpp"

namespace avar::kinematics {

struct DhChain {
  std::string name;
  std::vector<DhRow> rows;  ///< standard DH; each row's `where` is its line
  SourceLocation where;     ///< the `chain` line
};

/// Reads every chain of a file, in file order. Throws InputError for: a file that cannot be
/// opened, a malformed `chain` line (missing or extra words, a dof that is not a positive
/// integer), a duplicate chain name, a joint row outside a chain or beyond its dof, a row that
/// is not six numbers, a chain with fewer rows than its dof, a file with no chain. The values
/// themselves (finite, lower <= upper) are checked, at their row, by chain_from_standard_dh.
std::vector<DhChain> read_dh_chains(const std::string& path);

/// The same from a stream; `file` names it in errors.
std::vector<DhChain> read_dh_chains(std::istream& in, const std::string& file);

}  // namespace avar::kinematics
