// The stiffness is \f$ K = \int_\Omega B^T C B \, dx
// and we forgot to close the formula.
int main() { return 0; }
