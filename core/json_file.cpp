#include "core/json_file.hpp"

#include <algorithm>
#include <iterator>
#include <map>
#include <vector>

#include <fmt/format.h>

#include "core/errors.hpp"
#include "core/text_check.hpp"

namespace terracal {
namespace {

using Json = nlohmann::json;

// An iterator over the text that records how far the parser has read: nlohmann's SAX events carry
// no position, and a duplicate key should be reported at its line and column.
class TrackedChars {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackedChars(const char* p, const char** read_to) : p_(p), read_to_(read_to) {}
  reference operator*() const { return *p_; }
  TrackedChars& operator++() {
    *read_to_ = ++p_;
    return *this;
  }
  bool operator==(const TrackedChars& o) const { return p_ == o.p_; }
  bool operator!=(const TrackedChars& o) const { return p_ != o.p_; }

 private:
  const char* p_;
  const char** read_to_;
};

// A value's place in the document: an object with the keys seen so far (and where each was first
// seen), or an array with the index of its current element.
struct Frame {
  bool array = false;
  std::size_t index = 0;
  std::string key;
  std::map<std::string, std::size_t> keys;
};

// A non-zero number that strtod rounds to 0 (1e-400): nlohmann keeps the 0, the CSV reader refuses
// it (from_chars says out of range), and both readers should agree.
bool rounds_to_zero(double value, std::string_view token) {
  const std::string_view mantissa = token.substr(0, token.find_first_of("eE"));
  return value == 0 && mantissa.find_first_of("123456789") != std::string_view::npos;
}

// Builds the document with nlohmann's own DOM builder (json::parse uses the same class; it lives in
// nlohmann's detail namespace, unchanged through 3.x), and refuses what it lets pass or reports
// without a position: a key twice in one object (nlohmann keeps the last), numbers out of range,
// syntax errors (with line and column computed here, the quoted text shortened).
class StrictSax : public nlohmann::detail::json_sax_dom_parser<Json> {
  using Base = nlohmann::detail::json_sax_dom_parser<Json>;

 public:
  StrictSax(Json& root, const std::string& path, const std::string& what, std::string_view text, const char** read_to)
      : Base(root, true), path_(path), what_(what), text_(text), read_to_(read_to) {}

  bool null() {
    enter();
    return Base::null();
  }
  bool boolean(bool v) {
    enter();
    return Base::boolean(v);
  }
  bool number_integer(number_integer_t v) {
    enter();
    return Base::number_integer(v);
  }
  bool number_unsigned(number_unsigned_t v) {
    enter();
    return Base::number_unsigned(v);
  }
  bool number_float(number_float_t v, const string_t& s) {
    enter();
    // The parser may have read one character past the number: the token is found where it ends.
    if (rounds_to_zero(v, s)) fail(text_.rfind(s, offset() - std::min(offset(), s.size())), out_of_range_number(s));
    return Base::number_float(v, s);
  }
  bool string(string_t& v) {
    enter();
    return Base::string(v);
  }
  bool binary(binary_t& v) {
    enter();
    return Base::binary(v);
  }
  bool start_object(std::size_t n) {
    enter();
    frames_.emplace_back();
    return Base::start_object(n);
  }
  bool end_object() {
    frames_.pop_back();
    return Base::end_object();
  }
  bool start_array(std::size_t n) {
    enter();
    frames_.emplace_back().array = true;
    return Base::start_array(n);
  }
  bool end_array() {
    frames_.pop_back();
    return Base::end_array();
  }
  bool key(string_t& k);
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& last_token, const Exception& ex);

 private:
  // Before each value: in an array, the value is the next element.
  void enter() {
    if (!frames_.empty() && frames_.back().array) frames_.back().key = fmt::format("[{}]", frames_.back().index++);
  }
  std::size_t offset() const { return static_cast<std::size_t>(*read_to_ - text_.data()); }
  std::string key_path() const;
  [[noreturn]] void fail(std::size_t at, const std::string& what) const;

  std::string path_, what_;
  std::string_view text_;
  const char** read_to_;
  std::vector<Frame> frames_;
};

bool StrictSax::key(string_t& k) {
  // The parser has just read the key's closing quote; the key is reported at its opening quote,
  // the first quote before that is not escaped.
  std::size_t at = offset() - 1;
  do --at;
  while (at > 0 && (text_[at] != '"' || text_[at - 1] == '\\'));
  Frame& f = frames_.back();
  f.key = k;
  const auto [first, fresh] = f.keys.try_emplace(k, at);
  if (!fresh) {
    const LineColumn was = line_column(text_, first->second);
    fail(at, fmt::format("duplicate key (first at line {}, column {}); expected each key once in an object", was.line,
                         was.column));
  }
  return Base::key(k);
}

std::string StrictSax::key_path() const {
  std::string out;
  for (const auto& f : frames_) out += f.array || out.empty() ? f.key : "." + f.key;
  return out;
}

void StrictSax::fail(std::size_t at, const std::string& what) const {
  const std::string path = key_path();
  throw InputError(fmt::format("{}: {}{}", text_position(path_, text_, at),
                               path.empty() ? "" : fmt::format("key {}: ", excerpt(path)), what));
}

template <class Exception>
bool StrictSax::parse_error(std::size_t position, const std::string& last_token, const Exception& ex) {
  // nlohmann's position counts the character it stopped at; an overflowing number (error 406) is
  // reported where it ends, so it is moved back to where it begins.
  if (ex.id == 406) {
    enter();
    fail(position - std::min(position, last_token.size()), out_of_range_number(last_token));
  }
  // "[json.exception.parse_error.101] parse error at line 1, column 5: MESSAGE; last read: 'TOKEN'":
  // the position is given here in the form of every other message, the token shortened.
  std::string message = ex.what();
  const auto colon = message.find(": ", message.find("parse error"));
  if (colon != std::string::npos) message.erase(0, colon + 2);
  const std::string last_read = "; last read: '" + last_token + "'";
  if (const auto at = message.find(last_read); at != std::string::npos)
    message.replace(at, last_read.size(), "; last read: " + excerpt(last_token));
  throw InputError(fmt::format("{}: the {} is not valid JSON: {}",
                               text_position(path_, text_, position ? position - 1 : 0), what_, message));
}

}  // namespace

nlohmann::json read_json_file(const std::string& path, const std::string& what) {
  const std::string bytes = read_input_bytes(path, what);
  // The text check drops a UTF-8 byte-order mark; positions below count from after it.
  const std::string_view text = check_utf8_text(path, bytes);
  const char* read_to = text.data();
  Json root;
  StrictSax sax(root, path, what, text, &read_to);
  Json::sax_parse(TrackedChars(text.data(), &read_to), TrackedChars(text.data() + text.size(), &read_to), &sax);
  return root;
}

}  // namespace terracal
