#pragma once
/// gridloc's one exception type: thrown at public boundaries for bad input, with a message
/// that names the file, field and value at fault.
#include <stdexcept>
#include <string>

namespace gridloc {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace gridloc
