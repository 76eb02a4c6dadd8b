// Console text of long names and messages, shared by the hipair command and hipair-verify.
#pragma once

#include <string>

namespace hipair::console {

/// A name of the model (the model's, a part's, a parameter's) for a console line: the name itself
/// when it has at most 200 bytes, else its first 200 (not cutting a UTF-8 sequence) followed by
/// "... (N characters)". A 1 MB model name was printed whole by `show` and `validate` (hunt37's
/// finding); files (SVG titles, JSON) keep the whole name.
std::string shown_name(const std::string& name);

/// An error message for the console with each word longer than 200 bytes cut to its first 60 (not
/// inside a UTF-8 sequence) and its length: `--t-end` given a 100 000-digit value was echoed
/// whole in CLI11's "Could not convert: --t-end = ...", and a model's 1 MB key in the JSON
/// pointer of a reader's error, a certificate's 1 MB `claim` or unknown key in hipair-verify's
/// verdict (hunt37's and hunt38's findings). Other messages are unchanged.
std::string shortened_message(const std::string& message);

}  // namespace hipair::console
