#include "svg_check.h"
void test_svg_cov(const svg_test_opts *o) { (void)o; }
