// A scenario value that is either a number or a muparser expression of the simulated time t (seconds), such
// as a storm that ramps up:
//
//   auto speed = fw::io::Expression::parse("12 + 10*min(1, max(0, (t-20)/40))");   // m/s
//   speed(0.0);            // 12
//   speed(60.0);           // 22
//   speed.is_constant();   // false: it reads t
//   fw::io::Expression::parse("12").is_constant();                                  // true
//
// The language is muparser's (2.3): + - * / ^, comparisons, && ||, the ternary c ? a : b, the constants _pi
// and _e, and the functions sin cos tan asin acos atan atan2 sinh cosh tanh asinh acosh atanh log (natural)
// ln log2 log10 exp sqrt abs sign rint, and the variadic min max sum avg. The only variable is t; any other
// name is an error. A comma list ("1, 2") is rejected: one value per expression.
//
// Evaluation is deterministic (the same t gives the same bits) and thread-safe: concurrent calls on one
// Expression serialise on a small mutex (muparser evaluates on internal buffers). Copies are independent:
// each owns its own parser, bound to its own t, so no copy reads another's variable.
#pragma once

#include <memory>
#include <string>

namespace fw::io {

class Expression {
 public:
  /// The constant 0.
  Expression();
  /// A constant; text() is the shortest decimal form that reads back as the same double.
  static Expression constant(double value);
  /// Parses text as a muparser expression of t. Throws std::invalid_argument with muparser's message and the
  /// 0-based character position for a syntax error, an unknown variable or function (only t is allowed), an
  /// empty text or a comma list.
  static Expression parse(const std::string& text);

  Expression(const Expression& other);
  Expression& operator=(const Expression& other);
  Expression(Expression&& other) noexcept;
  Expression& operator=(Expression&& other) noexcept;
  ~Expression();

  /// The value at time t (seconds). May be inf or NaN where the formula is (e.g. sqrt of a negative).
  double operator()(double t) const;
  /// True when the expression does not read t (a number, or a formula of constants only).
  bool is_constant() const { return constant_; }
  /// The text as given to parse().
  const std::string& text() const { return text_; }

 private:
  struct Compiled;  // the muparser object and the t it is bound to, at a fixed address

  std::string text_;
  bool constant_ = true;
  double value_ = 0.0;                  // the value when constant_ (no parser needed then)
  std::unique_ptr<Compiled> compiled_;  // null when constant_
};

}  // namespace fw::io
