#include "io/Expression.hpp"

#include <fmt/format.h>
#include <muParser.h>

#include <mutex>
#include <numbers>
#include <stdexcept>

namespace fw::io {

struct Expression::Compiled {
  mu::Parser parser;
  double t = 0.0;  // muparser reads the variable through this address, so Compiled never moves
  std::mutex mutex;

  explicit Compiled(const std::string& text) {
    // muparser built with GCC defines _pi as 3.141592653589 (an upstream speed hack), 2.5e-13 off, so that
    // sin(_pi) gives 8e-13, not 1e-16. The nearest double to pi replaces it.
    parser.DefineConst("_pi", std::numbers::pi);
    parser.DefineVar("t", &t);
    parser.SetExpr(text);
  }
};

namespace {

std::string describe(const mu::Parser::exception_type& error) {
  std::string message = error.GetMsg();
  while (!message.empty() && (message.back() == '.' || message.back() == ' ')) message.pop_back();
  // Most muparser messages already say where; the ones that do not get the position appended.
  if (error.GetPos() >= 0 && message.find("position") == std::string::npos)
    message += fmt::format(" at position {}", error.GetPos());
  if (error.GetCode() == mu::ecUNASSIGNABLE_TOKEN)
    message +=
        fmt::format(" (unknown variable or function \"{}\"; the only variable is t)", error.GetToken());
  return message;
}

}  // namespace

Expression::Expression() : text_("0") {}

Expression Expression::constant(double value) {
  Expression expression;
  expression.text_ = fmt::format("{}", value);
  expression.value_ = value;
  return expression;
}

Expression Expression::parse(const std::string& text) {
  std::unique_ptr<Compiled> compiled;
  try {
    compiled = std::make_unique<Compiled>(text);
    // muparser compiles lazily on the first evaluation; force it so errors surface here, not mid-run.
    compiled->parser.Eval();
  } catch (const mu::Parser::exception_type& error) {
    throw std::invalid_argument(fmt::format("expression \"{}\": {}", text, describe(error)));
  }
  if (compiled->parser.GetNumResults() != 1)
    throw std::invalid_argument(fmt::format("expression \"{}\": one value expected, got a list of {}", text,
                                            compiled->parser.GetNumResults()));
  Expression expression;
  expression.text_ = text;
  expression.constant_ = compiled->parser.GetUsedVar().empty();
  if (expression.constant_)
    expression.value_ = compiled->parser.Eval();
  else
    expression.compiled_ = std::move(compiled);
  return expression;
}

Expression::Expression(const Expression& other)
    : text_(other.text_), constant_(other.constant_), value_(other.value_) {
  // A fresh parser bound to this copy's own t; the text parsed once already, so this cannot throw
  // invalid_argument.
  if (other.compiled_) {
    compiled_ = std::make_unique<Compiled>(text_);
    compiled_->parser.Eval();
  }
}

Expression& Expression::operator=(const Expression& other) {
  if (this != &other) *this = Expression(other);
  return *this;
}

Expression::Expression(Expression&& other) noexcept = default;
Expression& Expression::operator=(Expression&& other) noexcept = default;
Expression::~Expression() = default;

double Expression::operator()(double t) const {
  if (!compiled_) return value_;
  std::lock_guard lock(compiled_->mutex);
  compiled_->t = t;
  return compiled_->parser.Eval();
}

}  // namespace fw::io
