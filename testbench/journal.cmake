# SPDX-License-Identifier: MIT
# The journal file (src/journal/np_jfile.h) on its own; the sweep's and the
# link's journals are tested in sweep.cmake and usb.cmake.
np_test_program(test_journal test_journal.c)
np_add_cases(test_journal journal
  crc_kat round_trip torn_last_line torn_record corrupt_middle binding_mismatch cut_every_byte
  kill_resume open_run)
