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

inline XmlCheck check_xml(std::string_view x) {
  XmlCheck r;
  std::size_t i = 0;
  std::vector<std::string> stack;
  int roots = 0;
  auto fail = [&](const std::string& what) {
    if (r.ok) r.error = what + " at offset " + std::to_string(i);
    r.ok = false;
  };
  auto is_name_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ':' ||
           c == '.';
  };
  auto check_entities = [&](std::string_view text) {
    for (std::size_t k = 0; k < text.size(); ++k) {
      if (text[k] == '<') return fail("raw '<' in text or attribute"), false;
      if (text[k] != '&') continue;
      const std::size_t semi = text.find(';', k);
      if (semi == std::string_view::npos || semi - k < 2 || semi - k > 10)
        return fail("stray '&'"), false;
      const std::string_view ent = text.substr(k + 1, semi - k - 1);
      static const std::set<std::string_view> named = {"amp", "lt", "gt", "quot", "apos"};
      const bool numeric = ent.size() > 1 && ent[0] == '#';
      if (!numeric && !named.count(ent))
        return fail("unknown entity &" + std::string(ent) + ";"), false;
      k = semi;
    }
    return true;
  };
  while (i < x.size() && r.ok) {
    if (x[i] != '<') {
      const std::size_t next = x.find('<', i);
      const std::string_view text = x.substr(i, next == std::string_view::npos ? x.npos : next - i);
      if (stack.empty()) {
        for (char c : text)
          if (!std::isspace(static_cast<unsigned char>(c))) fail("text outside the root element");
      } else {
        check_entities(text);
      }
      i = next == std::string_view::npos ? x.size() : next;
      continue;
    }
    if (x.compare(i, 4, "<!--") == 0) {
      const std::size_t end = x.find("-->", i + 4);
      if (end == std::string_view::npos) return fail("unterminated comment"), r;
      i = end + 3;
      continue;
    }
    if (x.compare(i, 2, "<?") == 0) {
      const std::size_t end = x.find("?>", i + 2);
      if (end == std::string_view::npos) return fail("unterminated processing instruction"), r;
      i = end + 2;
      continue;
    }
    if (x.compare(i, 2, "<!") == 0) {  // <!DOCTYPE ...>
      const std::size_t end = x.find('>', i);
      if (end == std::string_view::npos) return fail("unterminated declaration"), r;
      i = end + 1;
      continue;
    }
    const bool closing = x.compare(i, 2, "</") == 0;
    i += closing ? 2 : 1;
    const std::size_t name_start = i;
    while (i < x.size() && is_name_char(x[i])) ++i;
    const std::string name(x.substr(name_start, i - name_start));
    if (name.empty()) return fail("empty element name"), r;
    if (closing) {
      while (i < x.size() && std::isspace(static_cast<unsigned char>(x[i]))) ++i;
      if (i >= x.size() || x[i] != '>') return fail("bad closing tag </" + name), r;
      ++i;
      if (stack.empty() || stack.back() != name)
        return fail("</" + name + "> does not close <" + (stack.empty() ? "" : stack.back()) + ">"),
               r;
      stack.pop_back();
      continue;
    }
    r.elements.push_back(name);
    std::set<std::string> seen;
    bool self_closing = false;
    while (r.ok) {
      while (i < x.size() && std::isspace(static_cast<unsigned char>(x[i]))) ++i;
      if (i >= x.size()) return fail("unterminated tag <" + name), r;
      if (x[i] == '>') {
        ++i;
        break;
      }
      if (x.compare(i, 2, "/>") == 0) {
        i += 2;
        self_closing = true;
        break;
      }
      const std::size_t a0 = i;
      while (i < x.size() && is_name_char(x[i])) ++i;
      const std::string attr(x.substr(a0, i - a0));
      if (attr.empty()) return fail("bad attribute in <" + name), r;
      if (!seen.insert(attr).second) return fail("duplicate attribute " + attr), r;
      if (i >= x.size() || x[i] != '=') return fail("attribute " + attr + " without value"), r;
      ++i;
      if (i >= x.size() || (x[i] != '"' && x[i] != '\'')) return fail("unquoted " + attr), r;
      const char q = x[i++];
      const std::size_t end = x.find(q, i);
      if (end == std::string_view::npos) return fail("unterminated value of " + attr), r;
      const std::string_view value = x.substr(i, end - i);
      check_entities(value);
      if (attr == "href" || attr == "xlink:href") r.hrefs.emplace_back(value);
      i = end + 1;
    }
    if (stack.empty()) ++roots;
    if (roots > 1) return fail("more than one root element"), r;
    if (!self_closing) stack.push_back(name);
  }
  if (r.ok && !stack.empty()) fail("unclosed <" + stack.back() + ">");
  if (r.ok && roots != 1) fail("no root element");
  return r;
}

}  // namespace skylight::testing_support
