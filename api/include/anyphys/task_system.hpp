#pragma once
// How a world spreads its work over threads. A game that has its own job system plugs it in by
// implementing TaskSystem (as with Box2D v3's enqueueTask / finishTask or Jolt's JobSystem) and
// setting WorldSettings::taskSystem; otherwise a world with WorldSettings::workers > 1 runs its
// own ThreadPool (anyphys/thread_pool.hpp). Results never depend on how many workers run or in which order: a backend
// that splits work gives every worker disjoint data and merges in a fixed order.
namespace anyphys {

class TaskSystem {
public:
    /// Work over items [begin, end), run by worker `worker` (0 <= worker < workerCount()).
    using RangeFn = void (*)(int begin, int end, int worker, void* context);

    virtual ~TaskSystem() = default;

    /// Workers that may run ranges at the same time, the thread that calls enqueue included
    /// (>= 1). Two ranges running at the same time always get different worker indices.
    virtual int workerCount() const = 0;

    /// Starts fn over items [0, count), split into ranges of at least `minRange` items (the
    /// last may be shorter), each item exactly once, on any workers and in any order. May run
    /// everything before returning. Returns a handle for finish (nullptr when nothing is left
    /// to wait for). `context` must stay valid until finish returns.
    virtual void* enqueue(int count, int minRange, RangeFn fn, void* context) = 0;

    /// Waits until every range of the enqueued work has run (the caller may run some itself).
    virtual void finish(void* handle) = 0;
};

/// Runs fn(begin, end, worker) over [0, count) on `tasks` and waits; serially on the calling
/// thread (worker 0) when tasks is null.
template <class Fn>
void parallelFor(TaskSystem* tasks, int count, int minRange, Fn& fn) {
    if (count <= 0) return;
    if (!tasks || tasks->workerCount() <= 1 || count <= minRange) {
        fn(0, count, 0);
        return;
    }
    const TaskSystem::RangeFn call = [](int begin, int end, int worker, void* context) {
        (*static_cast<Fn*>(context))(begin, end, worker);
    };
    tasks->finish(tasks->enqueue(count, minRange, call, const_cast<void*>(static_cast<const void*>(&fn))));
}

}  // namespace anyphys
