/* Preload shim for LeakSanitizer runs of the rendering tests (issue 13).
 * The OpenGL driver is a dlopen()ed module that is dlclose()d at exit; a
 * block its globals still own is then reported as a direct leak from
 * "<unknown module>" with no usable stack. Making dlclose() a no-op keeps
 * every module mapped, so LeakSanitizer sees those blocks as reachable and
 * any real leak keeps its symbols. Build and use:
 *   gcc -shared -fPIC -o keep-modules-loaded.so keep-modules-loaded.c
 *   LD_PRELOAD="$(gcc -print-file-name=libasan.so) ./keep-modules-loaded.so"
 */
int dlclose(void* handle)
{
  (void)handle;
  return 0;
}
