#include "hal/common/error.hpp"

namespace flat2d {

Error MakeError(std::string message) { return Error{std::move(message)}; }

}  // namespace flat2d
