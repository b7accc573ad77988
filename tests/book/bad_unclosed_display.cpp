int main() {
  // A display formula that never ends:
  // \f[
  //   K u = f
  return 0;
}
