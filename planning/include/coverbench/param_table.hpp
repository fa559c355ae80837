#pragma once
/// Typed planner parameters, declared once (docs/ADDING_A_PLANNER.md): a planner keeps its
/// parameters in a struct of its own and declares each one's spec (name, type, range, unit,
/// default, description) together with the member it fills. Experiments list, validate and sweep
/// the specs; the planner receives the struct filled (TypedPlanner) and never looks a parameter up
/// by name. Groups shared by several planners (the sweep direction) are structs of their own,
/// included whole. A declared default is the struct's own: a spec whose default differs from the
/// member's initial value is refused when the table is built (one source of truth; a planner's
/// registration fails on it, so no registered planner can have two defaults).
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "coverbench/planner.hpp"

namespace coverbench {

template <class P>
class ParamTable {
 public:
  /// A Number parameter into `member`.
  ParamTable& add(ParamSpec spec, double P::*member) {
    expect(spec, ParamType::Number);
    sameDefault(spec, ParamValue(P{}.*member));
    return put(std::move(spec), [member](P& p, const ParamValue& v) { p.*member = std::get<double>(v); });
  }
  /// An Integer parameter into `member`.
  ParamTable& add(ParamSpec spec, long long P::*member) {
    expect(spec, ParamType::Integer);
    sameDefault(spec, ParamValue(P{}.*member));
    return put(std::move(spec), [member](P& p, const ParamValue& v) { p.*member = std::get<long long>(v); });
  }
  /// A Bool parameter into `member`.
  ParamTable& add(ParamSpec spec, bool P::*member) {
    expect(spec, ParamType::Bool);
    sameDefault(spec, ParamValue(P{}.*member));
    return put(std::move(spec), [member](P& p, const ParamValue& v) { p.*member = std::get<bool>(v); });
  }
  /// A Choice parameter into the enum `member`: each choice's name with its value, in the order
  /// listed (the spec's choices are these names).
  template <class E>
  ParamTable& add(ParamSpec spec, E P::*member, std::vector<std::pair<std::string, E>> choices) {
    spec.type = ParamType::Choice;
    spec.choices.clear();
    for (const auto& c : choices) spec.choices.push_back(c.first);
    bool known_default = false;
    for (const auto& c : choices) known_default = known_default || ParamValue(c.first) == spec.default_value;
    if (!known_default) throw std::logic_error("parameter '" + spec.name + "': its default is none of its choices");
    for (const auto& c : choices)
      if (c.second == P{}.*member) sameDefault(spec, ParamValue(c.first));
    return put(std::move(spec), [member, choices](P& p, const ParamValue& v) {
      for (const auto& [name, value] : choices)
        if (std::get<std::string>(v) == name) {
          p.*member = value;
          return;
        }
      throw std::logic_error("choice '" + std::get<std::string>(v) + "' is not declared");
    });
  }
  /// Every parameter of a shared group, into the member that holds the group.
  template <class G>
  ParamTable& include(G P::*member, const ParamTable<G>& group) {
    for (std::size_t i = 0; i < group.specs().size(); ++i)
      put(group.specs()[i], [member, &group, i](P& p, const ParamValue& v) { group.setOne(p.*member, i, v); });
    return *this;
  }

  /// The declared specs, in declaration order (PlannerInfo::params).
  const std::vector<ParamSpec>& specs() const { return specs_; }

  /// The struct filled from resolved values (every declared parameter present and of its type,
  /// as experiments and the command line resolve them: std::logic_error otherwise).
  P fill(const Params& values) const {
    P p{};
    for (std::size_t i = 0; i < specs_.size(); ++i) {
      const auto it = values.all().find(specs_[i].name);
      if (it == values.all().end()) throw std::logic_error("parameter '" + specs_[i].name + "' was not resolved");
      setOne(p, i, it->second);
    }
    return p;
  }
  /// Sets parameter i of `p` (fill and include).
  void setOne(P& p, std::size_t i, const ParamValue& v) const {
    try {
      setters_.at(i)(p, v);
    } catch (const std::bad_variant_access&) {
      throw std::logic_error("parameter '" + specs_[i].name + "' has a value of another type");
    }
  }

 private:
  static void sameDefault(const ParamSpec& spec, const ParamValue& member_default) {
    if (spec.default_value != member_default)
      throw std::logic_error("parameter '" + spec.name + "': its declared default differs from its member's initial value");
  }
  static void expect(const ParamSpec& spec, ParamType type) {
    if (spec.type != type) throw std::logic_error("parameter '" + spec.name + "' is declared with another type than its member's");
  }
  ParamTable& put(ParamSpec spec, std::function<void(P&, const ParamValue&)> set) {
    for (const ParamSpec& s : specs_)
      if (s.name == spec.name) throw std::logic_error("parameter '" + spec.name + "' is declared twice");
    specs_.push_back(std::move(spec));
    setters_.push_back(std::move(set));
    return *this;
  }
  std::vector<ParamSpec> specs_;
  std::vector<std::function<void(P&, const ParamValue&)>> setters_;
};

/// A planner whose parameters are the struct P, declared by a ParamTable<P>: it implements
/// planWith(problem, params, budget) and receives the struct filled from the problem's values.
template <class P>
class TypedPlanner : public Planner {
 public:
  explicit TypedPlanner(const ParamTable<P>& table) : table_(&table) {}
  PlanResult plan(const Problem& problem, const Budget& budget) final {
    return planWith(problem, table_->fill(problem.params), budget);
  }

 protected:
  virtual PlanResult planWith(const Problem& problem, const P& params, const Budget& budget) = 0;

 private:
  const ParamTable<P>* table_;
};

/// The PlannerInfo of an in-tree planner T, a TypedPlanner of the parameters `table` declares:
/// `info` (its name, version, code folders, summary, reference and promise, written with
/// designated initializers) with the table's specs and a maker of T(args...).
template <class T, class P, class... Args>
PlannerInfo typedPlannerInfo(PlannerInfo info, const ParamTable<P>& table, Args... args) {
  info.params = table.specs();
  info.make = [args...] { return std::make_unique<T>(args...); };
  return info;
}

}  // namespace coverbench
