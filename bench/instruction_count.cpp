#include "instruction_count.hpp"

// valgrind's client requests are a few no-op instructions when the program runs natively. Without
// valgrind's headers the functions do nothing at all.
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define ANYPHYS_HAVE_CALLGRIND 1
#else
#define ANYPHYS_HAVE_CALLGRIND 0
#endif

namespace anyphys::bench {

#if ANYPHYS_HAVE_CALLGRIND
bool underValgrind() { return RUNNING_ON_VALGRIND != 0; }
void startCountingInstructions() {
    CALLGRIND_START_INSTRUMENTATION;
    CALLGRIND_TOGGLE_COLLECT;
}
void stopCountingInstructions() {
    CALLGRIND_TOGGLE_COLLECT;
    CALLGRIND_STOP_INSTRUMENTATION;
}
void dumpInstructionCount(const std::string& label) { CALLGRIND_DUMP_STATS_AT(label.c_str()); }
#else
bool underValgrind() { return false; }
void startCountingInstructions() {}
void stopCountingInstructions() {}
void dumpInstructionCount(const std::string&) {}
#endif

}  // namespace anyphys::bench
