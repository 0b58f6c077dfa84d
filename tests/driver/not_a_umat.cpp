// A shared library without a UMAT entry, for ecm-point --umat's refusal of one
// (tests/driver/umat_driver_test.cpp).
extern "C" __attribute__((visibility("default"))) double not_a_umat(double x) { return 2.0 * x; }
