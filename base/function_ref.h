#pragma once
// A non-owning reference to a callable (as C++26's std::function_ref): one type for every
// callable of a signature, so a template taking it is compiled once instead of once per lambda.
// Build time, not speed: the call is indirect.

#include <memory>
#include <type_traits>
#include <utility>

namespace rtlab {

template <class Sig>
class FunctionRef;

/// Calls the referenced callable, which must outlive the FunctionRef.
template <class R, class... Args>
class FunctionRef<R(Args...)> {
public:
    template <class F>
    requires(!std::is_same_v<std::remove_cvref_t<F>, FunctionRef> &&
             std::is_invocable_r_v<R, F&, Args...>)
        FunctionRef(F& f)  // NOLINT(google-explicit-constructor): passed where the callable was
        : object_(const_cast<void*>(static_cast<const void*>(std::addressof(f))))
        , call_([](void* o, Args... args) -> R {
            return (*static_cast<F*>(o))(std::forward<Args>(args)...);
        }) {}

    R operator()(Args... args) const { return call_(object_, std::forward<Args>(args)...); }

private:
    void* object_;
    R (*call_)(void*, Args...);
};

}  // namespace rtlab
