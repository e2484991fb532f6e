#pragma once
// Three equal rooms hanging below a corridor, each through a door in its top wall (unit
// coordinates): from a point of a room, with any range, the three rooms look the same.
#include "gridloc/engine/disambiguation/region.hpp"

namespace gridloc::test {

inline Area comb_rooms() {
  return Area{{{0, 0},   {2, 0},   {2, 2},   {1.2, 2}, {1.2, 2.5}, {3.8, 2.5}, {3.8, 2},
               {3, 2},   {3, 0},   {5, 0},   {5, 2},   {4.2, 2},   {4.2, 2.5}, {6.8, 2.5},
               {6.8, 2}, {6, 2},   {6, 0},   {8, 0},   {8, 2},     {7.2, 2},   {7.2, 2.5},
               {8, 2.5}, {8, 3.5}, {0, 3.5}, {0, 2.5}, {0.8, 2.5}, {0.8, 2},   {0, 2}},
              {}};
}

}  // namespace gridloc::test
