// Names of the error kinds, for reports and test messages.
#include "core/xy/gcode/error.hpp"

namespace ap::xy_gcode {

const char* error_name(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::None: return "None";
    case ErrorKind::LineTooLong: return "LineTooLong";
    case ErrorKind::BadCharacter: return "BadCharacter";
    case ErrorKind::UnknownWord: return "UnknownWord";
    case ErrorKind::MisplacedN: return "MisplacedN";
    case ErrorKind::BadNumber: return "BadNumber";
    case ErrorKind::TooManyDecimals: return "TooManyDecimals";
    case ErrorKind::NumberOutOfRange: return "NumberOutOfRange";
    case ErrorKind::UnsupportedG: return "UnsupportedG";
    case ErrorKind::ModalGroupConflict: return "ModalGroupConflict";
    case ErrorKind::DuplicateWord: return "DuplicateWord";
    case ErrorKind::UnclosedComment: return "UnclosedComment";
    case ErrorKind::MissingN: return "MissingN";
    case ErrorKind::MissingGorM: return "MissingGorM";
    case ErrorKind::BadSpacing: return "BadSpacing";
    case ErrorKind::NoMotionMode: return "NoMotionMode";
    case ErrorKind::PositionOutOfRange: return "PositionOutOfRange";
    case ErrorKind::ArcWithoutCentre: return "ArcWithoutCentre";
    case ErrorKind::ArcZeroRadius: return "ArcZeroRadius";
    case ErrorKind::ArcRadiusMismatch: return "ArcRadiusMismatch";
    case ErrorKind::UnusedWord: return "UnusedWord";
    case ErrorKind::BadFeed: return "BadFeed";
  }
  return "?";
}

}  // namespace ap::xy_gcode
