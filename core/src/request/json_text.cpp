// Parsing a JSON text (op.h json_from_text): the one place a document or an
// op file becomes JSON, so that their errors read alike.
#include <string>

#include "anisoform/error.h"
#include "anisoform/op.h"

namespace aniso {

namespace {

// nlohmann's message without its "[json.exception.KIND.ID] " prefix.
std::string plain_message(const Json::exception& error) {
  const std::string message = error.what();
  const std::size_t end = message.rfind("[json.exception", 0) == 0 ? message.find("] ") : std::string::npos;
  return end == std::string::npos ? message : message.substr(end + 2);
}

// The number an out_of_range error quotes ("number overflow parsing '1e400'").
std::string quoted_number(const std::string& message) {
  const std::size_t open = message.find('\'');
  const std::size_t close = open == std::string::npos ? open : message.find('\'', open + 1);
  return close == std::string::npos ? message : message.substr(open + 1, close - open - 1);
}

}  // namespace

Json json_from_text(const std::string& text, const std::string& what) {
  try {
    return Json::parse(text);
  } catch (const Json::parse_error& error) {
    fail(ErrorCode::BadParameter, what + " is not valid JSON: " + error.what());
  } catch (const Json::out_of_range& error) {
    fail(ErrorCode::BadParameter, what + " holds a number out of range: " + quoted_number(plain_message(error)) +
                                      " (a JSON number must be a finite double, at most about 1.8e308)");
  } catch (const Json::exception& error) {
    fail(ErrorCode::BadParameter, what + " is not valid JSON: " + plain_message(error));
  }
}

}  // namespace aniso
