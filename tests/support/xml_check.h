// Test helper: a small XML well-formedness checker for the SVG and HTML the report writes (no XML
// library is a dependency of the project). Checks: balanced and properly nested elements,
// attribute syntax (name="value" or name='value', each name once per element), no raw '<' or
// stray '&' in text or attribute values (only &name; and &#N; / &#xN; entities), one root element,
// and it collects the values of every href / xlink:href attribute.
#pragma once

#include <cctype>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace skylight::testing_support {

struct XmlCheck {
  bool ok = true;
  std::string error;                  // first problem, with its byte offset
  std::vector<std::string> hrefs;     // values of href and xlink:href attributes
  std::vector<std::string> elements;  // names of all elements, in document order
};

namespace detail {

// The checker's state while it walks the text once, left to right.
class XmlChecker {
 public:
  explicit XmlChecker(std::string_view x) : x_(x) {}

  XmlCheck run() {
    while (i_ < x_.size() && r_.ok) {
      if (x_[i_] != '<')
        text();
      else if (!skip_markup())
        tag();
    }
    if (r_.ok && !stack_.empty()) fail("unclosed <" + stack_.back() + ">");
    if (r_.ok && roots_ != 1) fail("no root element");
    return r_;
  }

 private:
  void fail(const std::string& what) {
    if (r_.ok) r_.error = what + " at offset " + std::to_string(i_);
    r_.ok = false;
  }
  static bool is_name_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ':' ||
           c == '.';
  }
  void skip_space() {
    while (i_ < x_.size() && std::isspace(static_cast<unsigned char>(x_[i_]))) ++i_;
  }
  std::string name() {
    const std::size_t start = i_;
    while (i_ < x_.size() && is_name_char(x_[i_])) ++i_;
    return std::string(x_.substr(start, i_ - start));
  }
  void check_entities(std::string_view text) {
    for (std::size_t k = 0; k < text.size(); ++k) {
      if (text[k] == '<') return fail("raw '<' in text or attribute");
      if (text[k] != '&') continue;
      const std::size_t semi = text.find(';', k);
      if (semi == std::string_view::npos || semi - k < 2 || semi - k > 10) return fail("stray '&'");
      const std::string_view ent = text.substr(k + 1, semi - k - 1);
      static const std::set<std::string_view> named = {"amp", "lt", "gt", "quot", "apos"};
      const bool numeric = ent.size() > 1 && ent[0] == '#';
      if (!numeric && !named.count(ent)) return fail("unknown entity &" + std::string(ent) + ";");
      k = semi;
    }
  }
  // Text up to the next '<': only white space outside the root element.
  void text() {
    const std::size_t next = x_.find('<', i_);
    const std::string_view t = x_.substr(i_, next == std::string_view::npos ? x_.npos : next - i_);
    if (stack_.empty()) {
      for (char c : t)
        if (!std::isspace(static_cast<unsigned char>(c))) fail("text outside the root element");
    } else {
      check_entities(t);
    }
    i_ = next == std::string_view::npos ? x_.size() : next;
  }
  // Comments, processing instructions and declarations (<!DOCTYPE ...>): skipped; false when
  // the markup at i_ is a tag.
  bool skip_markup() {
    struct Kind {
      std::string_view open, close, what;
    };
    for (const Kind& k :
         {Kind{"<!--", "-->", "comment"}, Kind{"<?", "?>", "processing instruction"},
          Kind{"<!", ">", "declaration"}}) {
      if (x_.compare(i_, k.open.size(), k.open) != 0) continue;
      const std::size_t end = x_.find(k.close, i_ + (k.close == ">" ? 0 : k.open.size()));
      if (end == std::string_view::npos)
        fail("unterminated " + std::string(k.what));
      else
        i_ = end + k.close.size();
      return true;
    }
    return false;
  }
  void tag() {
    const bool closing = x_.compare(i_, 2, "</") == 0;
    i_ += closing ? 2 : 1;
    const std::string n = name();
    if (n.empty()) return fail("empty element name");
    if (closing) return closing_tag(n);
    r_.elements.push_back(n);
    bool self_closing = false;
    if (!attributes(n, self_closing)) return;
    if (stack_.empty()) ++roots_;
    if (roots_ > 1) return fail("more than one root element");
    if (!self_closing) stack_.push_back(n);
  }
  void closing_tag(const std::string& n) {
    skip_space();
    if (i_ >= x_.size() || x_[i_] != '>') return fail("bad closing tag </" + n);
    ++i_;
    if (stack_.empty() || stack_.back() != n)
      return fail("</" + n + "> does not close <" + (stack_.empty() ? "" : stack_.back()) + ">");
    stack_.pop_back();
  }
  // The attributes of <n ...> up to '>' or '/>'; false on an error.
  bool attributes(const std::string& n, bool& self_closing) {
    std::set<std::string> seen;
    while (r_.ok) {
      skip_space();
      if (i_ >= x_.size()) return fail("unterminated tag <" + n), false;
      if (x_[i_] == '>') {
        ++i_;
        return true;
      }
      if (x_.compare(i_, 2, "/>") == 0) {
        i_ += 2;
        self_closing = true;
        return true;
      }
      const std::string attr = name();
      if (attr.empty()) return fail("bad attribute in <" + n), false;
      if (!seen.insert(attr).second) return fail("duplicate attribute " + attr), false;
      if (i_ >= x_.size() || x_[i_] != '=')
        return fail("attribute " + attr + " without value"), false;
      ++i_;
      if (i_ >= x_.size() || (x_[i_] != '"' && x_[i_] != '\''))
        return fail("unquoted " + attr), false;
      const char q = x_[i_++];
      const std::size_t end = x_.find(q, i_);
      if (end == std::string_view::npos) return fail("unterminated value of " + attr), false;
      const std::string_view value = x_.substr(i_, end - i_);
      check_entities(value);
      if (attr == "href" || attr == "xlink:href") r_.hrefs.emplace_back(value);
      i_ = end + 1;
    }
    return false;
  }

  std::string_view x_;
  std::size_t i_ = 0;
  XmlCheck r_;
  std::vector<std::string> stack_;
  int roots_ = 0;
};

}  // namespace detail

inline XmlCheck check_xml(std::string_view x) {
  return detail::XmlChecker(x).run();
}

}  // namespace skylight::testing_support
