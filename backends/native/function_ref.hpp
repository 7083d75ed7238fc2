#pragma once
// A non-owning reference to a callable, for callbacks that run only during the call that takes
// them (tree queries, force evaluation). Unlike std::function it never allocates, whatever the
// lambda captures, so per-step callbacks cost no heap traffic.
#include <memory>
#include <type_traits>
#include <utility>

namespace anyphys::native {

template <class Signature>
class FunctionRef;

template <class R, class... Args>
class FunctionRef<R(Args...)> {
public:
    template <class F, class = std::enable_if_t<!std::is_same_v<std::remove_cvref_t<F>, FunctionRef>>>
    FunctionRef(F&& f)  // NOLINT: implicit, like std::function
        : object_(const_cast<void*>(static_cast<const void*>(std::addressof(f)))),
          call_([](void* object, Args... args) -> R {
              return (*static_cast<std::remove_reference_t<F>*>(object))(std::forward<Args>(args)...);
          }) {}

    R operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

private:
    void* object_;
    R (*call_)(void*, Args...);
};

}  // namespace anyphys::native
