function bench_ehl_mex(root, calls)
%BENCH_EHL_MEX  Per-call cost of the force element through MEX: the timed loop of
%   tests/c/test_ehl.c and examples/bench_element.rs (the harmonic method's fitted laws with
%   damping, 7006 at 3000 rpm, warm state, displaced, with rates and a turning cage), through
%   EHL_EVALUATE and through ehl_mex('evaluate', ...) directly.
if nargin < 2, calls = 20000; end
c = ehl_case(fullfile(root, 'examples', '7006.toml'), 3000);
e = ehl_element('fitted', c, fullfile(root, 'crates', 'ehl-bearing-py', 'tests', 'data', ...
                'fitted_7006_3000rpm_harmonic.json'));
q0 = ehl_equilibrium(e, c);
ws = c.inner_speed_rad_s;
wc = ehl_cage_speed(e, ws, 0);
v = [1e-4; -2e-4; 1e-4; 1e-3; -1e-3];
q = q0;
ehl_evaluate(e, q, v, ws, 0, 0);
tic;
for i = 1:calls
  t = i * 1e-5;
  q(2) = q0(2) + 1e-8 * sin(1e3 * t);
  [R, K, C] = ehl_evaluate(e, q, v, ws, 0, wc * t); %#ok<ASGLU>
end
dt = toc;
fprintf('force element through MEX, ehl_evaluate.m: %d calls, %.2f us per call\n', calls, 1e6 * dt / calls);
s = e.state;
id = e.id;
tic;
for i = 1:calls
  t = i * 1e-5;
  q(2) = q0(2) + 1e-8 * sin(1e3 * t);
  [R, K, C] = ehl_mex('evaluate', id, s, q, v, ws, 0, wc * t); %#ok<ASGLU>
end
dt2 = toc;
fprintf('force element through MEX, ehl_mex(''evaluate'', ...) directly: %d calls, %.2f us per call\n', ...
        calls, 1e6 * dt2 / calls);
tic;
for i = 1:calls
  t = i * 1e-5;
  q(2) = q0(2) + 1e-8 * sin(1e3 * t);
end
dt3 = toc;
fprintf('the loop alone (no call): %.2f us per iteration\n', 1e6 * dt3 / calls);
tic;
for i = 1:calls
  n = ehl_mex('count'); %#ok<NASGU>
end
dt4 = toc;
fprintf('an empty MEX call (ehl_mex(''count'')): %.2f us per call\n', 1e6 * dt4 / calls);
ehl_free(c, e);
end
