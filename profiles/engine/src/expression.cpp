// SPDX-License-Identifier: MIT
#include "hil/profiles/expression.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstdlib>

#include "hil/profiles/decimal.hpp"

namespace hil::profiles {

struct Expression::Node {
  enum class Kind { number, string, name, unary_minus, not_, binary, chain, in_list, call };
  Kind kind = Kind::number;
  long double number = 0;
  std::string text;  // string literal, name, operator or function name
  std::vector<std::shared_ptr<const Node>> args;
  std::vector<std::string> ops;  // chain operators
};

namespace {

using NodePtr = std::shared_ptr<const Expression::Node>;
using Node = Expression::Node;

class Parser {
 public:
  explicit Parser(std::string_view s) : s_(s) {}

  std::expected<NodePtr, std::string> run() {
    auto n = parse_or();
    if (!n) return n;
    skip();
    if (pos_ != s_.size()) return fail("unexpected text");
    return n;
  }

 private:
  std::string_view s_;
  std::size_t pos_ = 0;
  int depth_ = 0;

  std::unexpected<std::string> fail(std::string_view what) const {
    return std::unexpected(fmt::format("{} at column {} of '{}'", what, pos_ + 1, s_));
  }
  void skip() {
    while (pos_ < s_.size() && (s_[pos_] == ' ' || s_[pos_] == '\t')) ++pos_;
  }
  bool eat(std::string_view tok) {
    skip();
    if (s_.substr(pos_).starts_with(tok)) {
      // keywords must not be followed by a name character
      if (std::isalpha(static_cast<unsigned char>(tok.back())) && pos_ + tok.size() < s_.size()) {
        const char c = s_[pos_ + tok.size()];
        if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.') return false;
      }
      pos_ += tok.size();
      return true;
    }
    return false;
  }
  static NodePtr make(Node n) { return std::make_shared<const Node>(std::move(n)); }

  std::expected<NodePtr, std::string> parse_or() {
    if (++depth_ > 64) return fail("expression nested too deeply");
    auto l = parse_and();
    while (l && (eat("||") || eat("or"))) {
      auto r = parse_and();
      if (!r) return r;
      l = make(Node{Node::Kind::binary, 0, "||", {*l, *r}, {}});
    }
    --depth_;
    return l;
  }
  std::expected<NodePtr, std::string> parse_and() {
    auto l = parse_not();
    while (l && (eat("&&") || eat("and"))) {
      auto r = parse_not();
      if (!r) return r;
      l = make(Node{Node::Kind::binary, 0, "&&", {*l, *r}, {}});
    }
    return l;
  }
  std::expected<NodePtr, std::string> parse_not() {
    skip();
    if ((pos_ < s_.size() && s_[pos_] == '!' && !(pos_ + 1 < s_.size() && s_[pos_ + 1] == '='))) {
      ++pos_;
      if (++depth_ > 64) return fail("expression nested too deeply");
      auto a = parse_not();
      --depth_;
      if (!a) return a;
      return make(Node{Node::Kind::not_, 0, "!", {*a}, {}});
    }
    if (eat("not")) {
      if (++depth_ > 64) return fail("expression nested too deeply");
      auto a = parse_not();
      --depth_;
      if (!a) return a;
      return make(Node{Node::Kind::not_, 0, "!", {*a}, {}});
    }
    return parse_cmp();
  }
  std::expected<NodePtr, std::string> parse_cmp() {
    auto first = parse_add();
    if (!first) return first;
    if (eat("in")) {
      skip();
      if (!eat("[")) return fail("expected '[' after 'in'");
      Node n{Node::Kind::in_list, 0, "in", {*first}, {}};
      if (!eat("]")) {
        do {
          auto e = parse_add();
          if (!e) return e;
          n.args.push_back(*e);
        } while (eat(","));
        if (!eat("]")) return fail("expected ']'");
      }
      return make(std::move(n));
    }
    Node chain{Node::Kind::chain, 0, "", {*first}, {}};
    for (;;) {
      std::string op;
      for (std::string_view o : {"<=", ">=", "==", "!=", "<", ">"})
        if (eat(o)) {
          op = o;
          break;
        }
      if (op.empty()) break;
      auto r = parse_add();
      if (!r) return r;
      chain.ops.push_back(op);
      chain.args.push_back(*r);
    }
    if (chain.ops.empty()) return first;
    return make(std::move(chain));
  }
  std::expected<NodePtr, std::string> parse_add() {
    auto l = parse_mul();
    for (;;) {
      if (!l) return l;
      skip();
      if (pos_ < s_.size() && (s_[pos_] == '+' || s_[pos_] == '-')) {
        std::string op(1, s_[pos_++]);
        auto r = parse_mul();
        if (!r) return r;
        l = make(Node{Node::Kind::binary, 0, op, {*l, *r}, {}});
      } else {
        return l;
      }
    }
  }
  std::expected<NodePtr, std::string> parse_mul() {
    auto l = parse_unary();
    for (;;) {
      if (!l) return l;
      skip();
      if (pos_ < s_.size() && (s_[pos_] == '*' || s_[pos_] == '/' || s_[pos_] == '%')) {
        std::string op(1, s_[pos_++]);
        auto r = parse_unary();
        if (!r) return r;
        l = make(Node{Node::Kind::binary, 0, op, {*l, *r}, {}});
      } else {
        return l;
      }
    }
  }
  std::expected<NodePtr, std::string> parse_unary() {
    skip();
    if (pos_ < s_.size() && s_[pos_] == '-') {
      ++pos_;
      if (++depth_ > 64) return fail("expression nested too deeply");
      auto a = parse_unary();
      --depth_;
      if (!a) return a;
      return make(Node{Node::Kind::unary_minus, 0, "-", {*a}, {}});
    }
    if (pos_ < s_.size() && s_[pos_] == '+') ++pos_;
    return parse_primary();
  }
  std::expected<NodePtr, std::string> parse_primary() {
    skip();
    if (pos_ >= s_.size()) return fail("expected a value");
    const char c = s_[pos_];
    if (c == '(') {
      ++pos_;
      auto e = parse_or();
      if (!e) return e;
      if (!eat(")")) return fail("expected ')'");
      return e;
    }
    if (c == '\'' || c == '"') {
      const auto end = s_.find(c, pos_ + 1);
      if (end == std::string_view::npos) return fail("unterminated string");
      Node n{Node::Kind::string, 0, std::string(s_.substr(pos_ + 1, end - pos_ - 1)), {}, {}};
      pos_ = end + 1;
      return make(std::move(n));
    }
    if (std::isdigit(static_cast<unsigned char>(c))) {
      std::size_t e = pos_;
      while (e < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[e])) || s_[e] == '.')) ++e;
      auto d = parse_decimal(s_.substr(pos_, e - pos_));
      if (!d) return fail(d.error());
      pos_ = e;
      return make(Node{Node::Kind::number, d->to_long_double(), "", {}, {}});
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      std::size_t e = pos_;
      while (e < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[e])) || s_[e] == '_' || s_[e] == '.')) ++e;
      std::string name(s_.substr(pos_, e - pos_));
      pos_ = e;
      if (eat("(")) {
        Node n{Node::Kind::call, 0, name, {}, {}};
        if (!eat(")")) {
          do {
            auto a = parse_or();
            if (!a) return a;
            n.args.push_back(*a);
          } while (eat(","));
          if (!eat(")")) return fail("expected ')' after function arguments");
        }
        static const std::vector<std::pair<std::string, std::size_t>> arity = {
            {"if", 3}, {"abs", 1}, {"min", 2}, {"max", 2}, {"defined", 1}, {"pow2", 1}, {"digit", 2}, {"bit", 2}};
        bool known = false;
        for (const auto& [f, a] : arity)
          if (f == name) {
            known = true;
            if (n.args.size() != a) return fail(fmt::format("{}() takes {} argument(s)", f, a));
          }
        if (!known) return fail(fmt::format("unknown function '{}'", name));
        if (name == "defined" && n.args[0]->kind != Node::Kind::name) return fail("defined() takes a name");
        return make(std::move(n));
      }
      return make(Node{Node::Kind::name, 0, std::move(name), {}, {}});
    }
    return fail(fmt::format("unexpected character '{}'", c));
  }
};

bool truthy(const ExprValue& v) {
  if (const auto* d = std::get_if<long double>(&v)) return *d != 0;
  return !std::get<std::string>(v).empty();
}

std::expected<bool, EvalError> compare(const ExprValue& a, const std::string& op, const ExprValue& b) {
  const bool an = std::holds_alternative<long double>(a), bn = std::holds_alternative<long double>(b);
  if (an != bn) {
    if (op == "==") return false;
    if (op == "!=") return true;
    return std::unexpected(
        EvalError{false, fmt::format("cannot compare '{}' {} '{}'", to_string(a), op, to_string(b))});
  }
  int c = 0;
  if (an) {
    const long double x = std::get<long double>(a), y = std::get<long double>(b);
    // Tolerance for values computed through divisions (e.g. rpm / 60 × feed constant).
    const long double tol = 1e-12L * std::max<long double>(1.0L, std::max(std::fabs(x), std::fabs(y)));
    c = std::fabs(x - y) <= tol ? 0 : (x < y ? -1 : 1);
  } else {
    c = std::get<std::string>(a).compare(std::get<std::string>(b));
    c = c < 0 ? -1 : (c > 0 ? 1 : 0);
  }
  if (op == "==") return c == 0;
  if (op == "!=") return c != 0;
  if (op == "<") return c < 0;
  if (op == "<=") return c <= 0;
  if (op == ">") return c > 0;
  return c >= 0;
}

std::expected<long double, EvalError> num(const ExprValue& v) {
  if (const auto* d = std::get_if<long double>(&v)) return *d;
  return std::unexpected(EvalError{false, fmt::format("'{}' is not a number", std::get<std::string>(v))});
}

std::expected<ExprValue, EvalError> eval(const Node& n, const Expression::Lookup& lookup) {
  using K = Node::Kind;
  switch (n.kind) {
    case K::number:
      return ExprValue{n.number};
    case K::string:
      return ExprValue{n.text};
    case K::name: {
      auto v = lookup(n.text);
      if (!v) return std::unexpected(EvalError{true, fmt::format("'{}' has no value", n.text)});
      return *v;
    }
    case K::unary_minus: {
      auto a = eval(*n.args[0], lookup);
      if (!a) return a;
      auto x = num(*a);
      if (!x) return std::unexpected(x.error());
      return ExprValue{-*x};
    }
    case K::not_: {
      auto a = eval(*n.args[0], lookup);
      if (!a) return a;
      return ExprValue{truthy(*a) ? 0.0L : 1.0L};
    }
    case K::binary: {
      auto a = eval(*n.args[0], lookup);
      if (!a) return a;
      if (n.text == "&&" && !truthy(*a)) return ExprValue{0.0L};
      if (n.text == "||" && truthy(*a)) return ExprValue{1.0L};
      auto b = eval(*n.args[1], lookup);
      if (!b) return b;
      if (n.text == "&&" || n.text == "||") return ExprValue{truthy(*b) ? 1.0L : 0.0L};
      auto x = num(*a);
      if (!x) return std::unexpected(x.error());
      auto y = num(*b);
      if (!y) return std::unexpected(y.error());
      if (n.text == "+") return ExprValue{*x + *y};
      if (n.text == "-") return ExprValue{*x - *y};
      if (n.text == "*") return ExprValue{*x * *y};
      if (*y == 0) return std::unexpected(EvalError{false, "division by zero"});
      if (n.text == "/") return ExprValue{*x / *y};
      return ExprValue{std::fmod(*x, *y)};
    }
    case K::chain: {
      auto left = eval(*n.args[0], lookup);
      if (!left) return left;
      for (std::size_t i = 0; i < n.ops.size(); ++i) {
        auto right = eval(*n.args[i + 1], lookup);
        if (!right) return right;
        auto c = compare(*left, n.ops[i], *right);
        if (!c) return std::unexpected(c.error());
        if (!*c) return ExprValue{0.0L};
        left = std::move(right);
      }
      return ExprValue{1.0L};
    }
    case K::in_list: {
      auto a = eval(*n.args[0], lookup);
      if (!a) return a;
      for (std::size_t i = 1; i < n.args.size(); ++i) {
        auto b = eval(*n.args[i], lookup);
        if (!b) return b;
        auto c = compare(*a, "==", *b);
        if (c && *c) return ExprValue{1.0L};
      }
      return ExprValue{0.0L};
    }
    case K::call: {
      if (n.text == "defined") return ExprValue{lookup(n.args[0]->text) ? 1.0L : 0.0L};
      if (n.text == "if") {
        auto c = eval(*n.args[0], lookup);
        if (!c) return c;
        return eval(*n.args[truthy(*c) ? 1 : 2], lookup);
      }
      std::vector<long double> xs;
      for (const auto& a : n.args) {
        auto v = eval(*a, lookup);
        if (!v) return v;
        auto x = num(*v);
        if (!x) return std::unexpected(x.error());
        xs.push_back(*x);
      }
      if (n.text == "abs") return ExprValue{std::fabs(xs[0])};
      if (n.text == "min") return ExprValue{std::min(xs[0], xs[1])};
      if (n.text == "max") return ExprValue{std::max(xs[0], xs[1])};
      if (n.text == "digit" || n.text == "bit") {
        // digit(x, n): n-th decimal digit from the right (n = 0 is the units); bit(x, n): bit n
        if (xs[1] < 0 || xs[1] > 62 || xs[0] < 0 || xs[0] > 9.0e18L) return ExprValue{0.0L};
        auto v = static_cast<unsigned long long>(std::floor(xs[0]));
        const auto k = static_cast<unsigned>(xs[1]);
        if (n.text == "bit") return ExprValue{static_cast<long double>((v >> k) & 1u)};
        for (unsigned i = 0; i < k && v; ++i) v /= 10;
        return ExprValue{static_cast<long double>(v % 10)};
      }
      // pow2(x): 1 when x is a positive integer power of two
      const long double x = xs[0];
      if (x < 1 || x != std::floor(x) || x > 9.0e18L) return ExprValue{0.0L};
      const auto u = static_cast<unsigned long long>(x);
      return ExprValue{(u & (u - 1)) == 0 ? 1.0L : 0.0L};
    }
  }
  return std::unexpected(EvalError{false, "bad expression node"});
}

void collect(const Node& n, std::vector<std::string>& out) {
  if (n.kind == Node::Kind::name) {
    for (const auto& s : out)
      if (s == n.text) return;
    out.push_back(n.text);
  }
  for (const auto& a : n.args) collect(*a, out);
}

}  // namespace

std::expected<Expression, std::string> Expression::parse(std::string_view text) {
  Parser p(text);
  auto root = p.run();
  if (!root) return std::unexpected(root.error());
  Expression e;
  e.root_ = *root;
  e.text_ = std::string(text);
  return e;
}

std::expected<ExprValue, EvalError> Expression::evaluate(const Lookup& lookup) const {
  if (!root_) return std::unexpected(EvalError{false, "empty expression"});
  return eval(*root_, lookup);
}

std::expected<bool, EvalError> Expression::test(const Lookup& lookup) const {
  auto v = evaluate(lookup);
  if (!v) return std::unexpected(v.error());
  return truthy(*v);
}

std::vector<std::string> Expression::names() const {
  std::vector<std::string> out;
  if (root_) collect(*root_, out);
  return out;
}

std::string to_string(const ExprValue& v) {
  if (const auto* s = std::get_if<std::string>(&v)) return *s;
  const long double d = std::get<long double>(v);
  if (d == std::floor(d) && std::fabs(d) < 1e18L) return fmt::format("{}", static_cast<long long>(d));
  return fmt::format("{:.10g}", static_cast<double>(d));
}

}  // namespace hil::profiles
