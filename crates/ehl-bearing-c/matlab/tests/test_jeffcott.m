function test_jeffcott(root, rust_json)
%TEST_JEFFCOTT  The MATLAB/Octave Jeffcott rotor example (jeffcott_rotor.m) against the Rust
%   rotor model on the same rotor (RUST_JSON: the output of
%   `cargo run --release -p ehl-bearing-c --example jeffcott_reference`): steady unbalance
%   amplitudes within 0.5 %. Prints both and 'N passed, M failed'; an error if any failed.
ref = jsondecode(fileread(rust_json));
r = jeffcott_rotor([], root);
passed = 0; failed = 0;
fprintf('Jeffcott rotor, %d steps, %d Newton iterations, %.2f s in Octave/MATLAB (Rust: %.2f s)\n', ...
        r.steps, r.newton_iterations, r.seconds, ref.seconds);
for name = {'amplitude_disk_y_m', 'amplitude_disk_z_m', 'amplitude_journal_a_y_m', ...
            'amplitude_journal_b_z_m', 'static_disk_y_m'}
  k = name{1};
  rel = abs(r.(k) / ref.(k) - 1);
  fprintf('  %-26s MEX %.10e  Rust %.10e  relative difference %.2e\n', k, r.(k), ref.(k), rel);
  if rel <= 5e-3
    passed = passed + 1;
  else
    failed = failed + 1;
    fprintf(2, 'FAIL: %s differs by %.3g %% (0.5 %% allowed)\n', k, 100 * rel);
  end
end
fprintf('%d passed, %d failed\n', passed, failed);
if failed > 0
  error('ehl:test', 'the Jeffcott rotor disagrees with the Rust rotor model');
end
end
