#pragma once
// A task system that runs every range on the calling thread, in reverse order, and only when
// finish is called: the stepping thread must never wait for a worker that has not started.
#include <algorithm>
#include <vector>

#include "anyphys/task_system.hpp"

namespace anyphys::test {

class LateReverseTasks final : public TaskSystem {
public:
    explicit LateReverseTasks(int workers) : workers_(workers) {}
    int workerCount() const override { return workers_; }
    void* enqueue(int count, int minRange, RangeFn fn, void* context) override {
        pending_.push_back({count, std::max(minRange, 1), fn, context});
        return &pending_.back();
    }
    void finish(void* handle) override {
        const Pending p = *static_cast<Pending*>(handle);
        pending_.pop_back();
        int worker = 0;
        for (int end = p.count; end > 0; end -= p.size) {
            const int begin = std::max(0, end - p.size);
            p.fn(begin, end, worker, p.context);
            worker = (worker + 1) % workers_;
        }
    }

private:
    struct Pending {
        int count, size;
        RangeFn fn;
        void* context;
    };
    int workers_;
    std::vector<Pending> pending_;
};

}  // namespace anyphys::test
