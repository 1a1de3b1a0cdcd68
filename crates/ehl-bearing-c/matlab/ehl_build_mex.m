function ehl_build_mex(libdir)
%EHL_BUILD_MEX  Build the MEX gateway ehl_mex over the ehl-bearing C library.
%   EHL_BUILD_MEX(LIBDIR) compiles ehl_mex.c in this folder against libehl_bearing_c in LIBDIR
%   (default: target/release of the repository, built by
%   `cargo build --release -p ehl-bearing-c`), in Octave with `mkoctfile --mex`, in MATLAB with
%   `mex`. The result, ehl_mex.mex (Octave) or ehl_mex.mexa64 (MATLAB), lands in this folder.
here = fileparts(mfilename('fullpath'));
if nargin < 1 || isempty(libdir)
  libdir = fullfile(here, '..', '..', '..', 'target', 'release');
end
inc = fullfile(here, '..', 'include');
src = fullfile(here, 'ehl_mex.c');
if exist('OCTAVE_VERSION', 'builtin')
  libdir = canonicalize_file_name(libdir);
  if isempty(libdir) || exist(fullfile(libdir, 'libehl_bearing_c.so'), 'file') ~= 2
    error('ehl:build', ['libehl_bearing_c.so not found; build it with ' ...
          '`cargo build --release -p ehl-bearing-c` or give its folder']);
  end
  out = fullfile(here, 'ehl_mex.mex');
  [status, text] = mkoctfile('--mex', '-O2', ['-I' inc], src, ['-L' libdir], ...
      '-lehl_bearing_c', ['-Wl,-rpath,' libdir], '-o', out);
  if status ~= 0
    error('ehl:build', 'mkoctfile failed:\n%s', text);
  end
else
  mex('-R2017b', ['-I' inc], src, ['-L' libdir], '-lehl_bearing_c', ...
      ['LDFLAGS=$LDFLAGS -Wl,-rpath,' libdir], '-outdir', here);
end
end
