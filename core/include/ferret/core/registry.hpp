#pragma once
// A variation point: implementations of one interface by name, each built from one
// options type. A module fills its registry by an explicit call (its
// register_builtins()), made where the registry is first used, never by static
// initializers (a static build drops those silently). Adding an implementation is one
// class and one add() line.
//
//   Registry<TetherController, ControllerOptions> r;
//   r.add("mpc", "the taut-tether MPC", [](const ControllerOptions& o) { ... });
//   auto controller = r.make(name, options, "--controller");
//
// `Traits` is what an entry says about itself besides its factory, known before anything
// is built (the backends: whether the simulator serves it; core/backend.hpp).

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

#include "ferret/core/error.hpp"

namespace ferret {

template <class Interface, class Options, class Traits = std::monostate>
class Registry {
 public:
  using Factory = std::function<std::unique_ptr<Interface>(const Options&)>;

  struct Entry {
    std::string name;
    std::string description;  ///< one line, for help texts and docs
    Factory factory;
    std::string label;  ///< how plots and reports print it (the name unless given)
    Traits traits;
  };

  /// Adds `name`. @throws std::logic_error when the name is taken (two implementations
  /// under one name is a programming error, not input) or the factory is empty.
  void add(std::string name, std::string description, Factory factory, std::string label = {},
           Traits traits = {}) {
    if (contains(name)) throw std::logic_error("registry: '" + name + "' is registered twice");
    if (!factory) throw std::logic_error("registry: '" + name + "' has no factory");
    if (label.empty()) label = name;
    entries_.push_back({std::move(name), std::move(description), std::move(factory),
                        std::move(label), std::move(traits)});
  }

  /// The traits `name` was added with. @throws std::logic_error for a name that is not
  /// registered (callers ask only for names a reader has checked).
  [[nodiscard]] const Traits& traits(std::string_view name) const {
    const Entry* e = find(name);
    if (e == nullptr)
      throw std::logic_error("registry: '" + std::string(name) + "' is not registered");
    return e->traits;
  }

  /// The label of `name`; `name` itself when it is not registered.
  [[nodiscard]] std::string label(std::string_view name) const {
    const Entry* e = find(name);
    return e != nullptr ? e->label : std::string(name);
  }

  [[nodiscard]] bool contains(std::string_view name) const { return find(name) != nullptr; }

  /// The names in the order they were added (the registration calls fix it: help texts
  /// and error messages do not change with the standard library).
  [[nodiscard]] std::vector<std::string> names() const {
    std::vector<std::string> out;
    out.reserve(entries_.size());
    for (const auto& e : entries_) out.push_back(e.name);
    return out;
  }

  [[nodiscard]] const std::vector<Entry>& entries() const { return entries_; }

  /// The entry of `name`, or null.
  [[nodiscard]] const Entry* find(std::string_view name) const {
    const auto it = std::find_if(entries_.begin(), entries_.end(),
                                 [&](const Entry& e) { return e.name == name; });
    return it == entries_.end() ? nullptr : &*it;
  }

  /// "one of a, b, c": what a valid name looks like, for an InputError.
  [[nodiscard]] std::string expected() const {
    return fmt::format("one of {}", fmt::join(names(), ", "));
  }

  /// Throws InputError(source, field, "one of <names>", name) unless `name` is registered.
  void check(std::string_view name, const std::string& source,
             const std::string& field = {}) const {
    if (!contains(name)) throw InputError(source, field, expected(), std::string(name));
  }

  /// A new `name` built from `options`. @throws InputError naming `source` (a file, an
  /// option such as "--controller") and `field`, listing the names, for an unknown name.
  [[nodiscard]] std::unique_ptr<Interface> make(std::string_view name, const Options& options,
                                                const std::string& source,
                                                const std::string& field = {}) const {
    const Entry* e = find(name);
    if (e == nullptr) throw InputError(source, field, expected(), std::string(name));
    return e->factory(options);
  }

 private:
  std::vector<Entry> entries_;
};

/// The registry `Fill` (a module's register_builtin_*()) fills, built the first time it is
/// asked for (a function-local static: once, thread-safe, after main() has started):
///
///   const WinchBackendRegistry& winch_backends() {
///     return filled_registry<WinchBackendRegistry, register_builtin_winch_backends>();
///   }
template <class R, void (*Fill)(R&)>
[[nodiscard]] const R& filled_registry() {
  static const R registry = [] {
    R r;
    Fill(r);
    return r;
  }();
  return registry;
}

}  // namespace ferret
