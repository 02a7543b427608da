/* SPDX-License-Identifier: MIT */
#include "np_vec.h"
