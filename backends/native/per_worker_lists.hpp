#pragma once
// One list per worker for a parallel walk that finds things, then joins them on the calling
// thread. The walk's ranges go to whichever worker is free, so any list may have to hold
// everything found: joining reserves that much in each, and a steady world never allocates.
#include <cstddef>
#include <vector>

namespace anyphys::native {

template <class T>
class PerWorkerLists {
public:
    /// One empty list per worker, keeping the capacity each had.
    void reset(int workers) {
        if (lists_.size() < static_cast<std::size_t>(workers)) lists_.resize(static_cast<std::size_t>(workers));
        for (std::vector<T>& list : lists_) list.clear();
    }

    std::vector<T>& of(int worker) { return lists_[static_cast<std::size_t>(worker)]; }

    /// Every list's items, worker after worker. The order still depends on which worker took
    /// which range: callers sort what they need deterministic.
    std::vector<T>& joined() {
        joined_.clear();
        for (const std::vector<T>& list : lists_) joined_.insert(joined_.end(), list.begin(), list.end());
        for (std::vector<T>& list : lists_) list.reserve(joined_.size());
        return joined_;
    }

private:
    std::vector<std::vector<T>> lists_;
    std::vector<T> joined_;
};

}  // namespace anyphys::native
