/* SPDX-License-Identifier: MIT */
#ifndef NP_VEC_H
#define NP_VEC_H
#endif
