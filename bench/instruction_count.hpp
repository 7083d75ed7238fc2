#pragma once
// Instruction counts of the timed steps, for runs under valgrind's callgrind
// (scripts/overhead_instructions.sh). Time on a shared virtual machine moves by 10 % between
// rounds, more than the 3 % a wrapper overhead may cost; the instructions a step executes do not
// move at all, so under callgrind the overhead rows give an exact, repeatable figure of the
// layer's extra work. Outside valgrind every call here does nothing.
#include <string>

namespace anyphys::bench {

/// True when the program runs under valgrind (one round of each comparison is then enough).
bool underValgrind();

/// Counts the instructions between these two calls. callgrind started with --instr-atstart=no
/// --collect-atstart=no counts nothing else, and runs the rest uninstrumented (about a tenth of
/// the slowdown).
void startCountingInstructions();
void stopCountingInstructions();

/// Writes what was counted since the last dump to a callgrind output file whose description is
/// `label`, and starts the next count from zero.
void dumpInstructionCount(const std::string& label);

}  // namespace anyphys::bench
