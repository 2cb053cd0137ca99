#include "core/vrml_field_filter.hpp"

#include <algorithm>
#include <cctype>

namespace palpate::detail {
namespace {

enum class Kind {
  word,
  string,
  open_brace,
  close_brace,
  open_bracket,
  close_bracket,
  open_paren,
  close_paren,
  end
};

struct Token {
  Kind kind = Kind::end;
  std::size_t begin = 0, end = 0;
};

// VRML's lexical rules, enough to find field boundaries: whitespace and commas separate, '#' starts
// a comment to the end of the line, strings are double-quoted with backslash escapes.
class Scanner {
 public:
  explicit Scanner(std::string_view text) : text_(text) {}

  Token next() {
    skip_space();
    Token t;
    t.begin = pos_;
    if (pos_ >= text_.size()) {
      t.end = pos_;
      return t;
    }
    const char c = text_[pos_];
    const auto single = [&](Kind kind) {
      t.kind = kind;
      t.end = ++pos_;
      return t;
    };
    switch (c) {
      case '{':
        return single(Kind::open_brace);
      case '}':
        return single(Kind::close_brace);
      case '[':
        return single(Kind::open_bracket);
      case ']':
        return single(Kind::close_bracket);
      case '(':
        return single(Kind::open_paren);
      case ')':
        return single(Kind::close_paren);
      case '"':
        ++pos_;
        while (pos_ < text_.size() && text_[pos_] != '"') pos_ += text_[pos_] == '\\' ? 2 : 1;
        pos_ = std::min(pos_ + 1, text_.size());
        t.kind = Kind::string;
        t.end = pos_;
        return t;
      default:
        while (pos_ < text_.size() && !is_separator(text_[pos_]) &&
               std::string_view("{}[]()\"#").find(text_[pos_]) == std::string_view::npos) {
          ++pos_;
        }
        t.kind = Kind::word;
        t.end = pos_;
        return t;
    }
  }

  Token peek() {
    const std::size_t saved = pos_;
    const Token t = next();
    pos_ = saved;
    return t;
  }

  std::string_view text(const Token& t) const { return text_.substr(t.begin, t.end - t.begin); }

  // Consumes tokens up to and including the one closing the group `open` started.
  Token skip_group() {
    int depth = 1;
    Token t;
    while (depth > 0) {
      t = next();
      if (t.kind == Kind::end) return t;
      if (t.kind == Kind::open_brace || t.kind == Kind::open_bracket || t.kind == Kind::open_paren) ++depth;
      if (t.kind == Kind::close_brace || t.kind == Kind::close_bracket || t.kind == Kind::close_paren)
        --depth;
    }
    return t;
  }

 private:
  static bool is_separator(char c) { return std::isspace(static_cast<unsigned char>(c)) || c == ','; }

  void skip_space() {
    while (pos_ < text_.size()) {
      if (is_separator(text_[pos_])) {
        ++pos_;
      } else if (text_[pos_] == '#') {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
      } else {
        break;
      }
    }
  }

  std::string_view text_;
  std::size_t pos_ = 0;
};

bool is_number(std::string_view word) {
  return !word.empty() && (std::isdigit(static_cast<unsigned char>(word[0])) || word[0] == '+' ||
                           word[0] == '-' || word[0] == '.');
}

// Consumes the value that follows a field name; returns the end of its last token.
std::size_t skip_value(Scanner& in, std::size_t fallback_end) {
  const Token first = in.next();
  const std::string_view word = in.text(first);
  switch (first.kind) {
    case Kind::open_bracket:
    case Kind::open_paren:
      return in.skip_group().end;
    case Kind::string:
      return first.end;
    case Kind::word:
      break;
    default:
      return fallback_end;  // no value: leave the rest alone
  }
  if (word == "NULL" || word == "TRUE" || word == "FALSE") return first.end;
  if (word == "USE" || word == "IS") return in.next().end;
  if (word == "DEF") {
    in.next();  // the name
    in.next();  // the node type
    if (in.next().kind != Kind::open_brace) return fallback_end;
    return in.skip_group().end;
  }
  if (in.peek().kind == Kind::open_brace) {  // a node: Type { ... }
    in.next();
    return in.skip_group().end;
  }
  if (!is_number(word)) return first.end;  // an enum value
  std::size_t end = first.end;
  for (Token t = in.peek(); t.kind == Kind::word && is_number(in.text(t)); t = in.peek()) end = in.next().end;
  return end;
}

struct OpenNode {
  std::string_view type;
  int brackets = 0;  // open [ ] inside this node's body: field names appear only at 0
};

}  // namespace

std::size_t remove_vrml_field(std::string& text, std::string_view field,
                              const std::vector<std::string>& node_types) {
  std::vector<std::pair<std::size_t, std::size_t>> cuts;
  {
    Scanner in(text);
    std::vector<OpenNode> open;
    std::string_view last_word;
    Kind last_kind = Kind::end;
    for (Token t = in.next(); t.kind != Kind::end; t = in.next()) {
      const std::string_view word = in.text(t);
      switch (t.kind) {
        case Kind::open_brace:
          open.push_back({last_kind == Kind::word ? last_word : std::string_view{}});
          break;
        case Kind::close_brace:
          if (!open.empty()) open.pop_back();
          break;
        case Kind::open_bracket:
          if (!open.empty()) ++open.back().brackets;
          break;
        case Kind::close_bracket:
          if (!open.empty()) --open.back().brackets;
          break;
        case Kind::word:
          if (word == field && !open.empty() && open.back().brackets == 0 &&
              !(last_kind == Kind::word && (last_word == "DEF" || last_word == "USE" || last_word == "IS")) &&
              std::find(node_types.begin(), node_types.end(), open.back().type) != node_types.end()) {
            cuts.emplace_back(t.begin, skip_value(in, t.end));
            last_kind = Kind::end;
            continue;
          }
          break;
        default:
          break;
      }
      last_word = word;
      last_kind = t.kind;
    }
  }
  for (const auto& [begin, end] : cuts) {
    for (std::size_t i = begin; i < end && i < text.size(); ++i) {
      if (text[i] != '\n' && text[i] != '\r') text[i] = ' ';
    }
  }
  return cuts.size();
}

}  // namespace palpate::detail
