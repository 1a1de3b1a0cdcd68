function result = jeffcott_rotor(params_file, root)
%JEFFCOTT_ROTOR  A Jeffcott rotor on two ehl-bearing elements, in plain MATLAB/Octave code.
%   RESULT = JEFFCOTT_ROTOR(PARAMS_FILE, ROOT) reads the rotor (jeffcott.json beside this file
%   by default) and integrates its unbalance response with Newmark's average-acceleration rule
%   (fixed step, Newton on the full equation each step: the bearing forces implicit), the same
%   scheme as the library's Rust rotor model, which examples/jeffcott_reference.rs runs on the
%   same rotor. ROOT is the repository root (for the case and the fitted laws).
%
%   The rotor: a disk (mass md) at mid-span of a massless shaft (stiffness ks per half, in y
%   and z) whose ends are journals (mass mj each) in a mirrored, axially preloaded pair of the
%   seed 7006 bearing with the harmonic method's fitted laws (with damping) at 3000 rpm; one
%   axial DOF for the whole rotor. DOFs: 1 axial x; 2-3 disk y, z; 4-5 journal A y, z; 6-7
%   journal B y, z. The bearings' tilts are held at zero. The equation of motion:
%     M*qdd + D*qd + K*q = f_const + f_unbalance(t) - sum_b L_b' * R_b(L_b*q + o_b, L_b*qd)
%   with R_b the reaction of bearing b (EHL_EVALUATE), L_b its DOF map and o_b its preload.
%
%   RESULT has the 1x amplitudes over the last revolutions (m): amplitude_disk_y_m,
%   amplitude_disk_z_m, amplitude_journal_a_y_m, amplitude_journal_b_z_m; static_disk_y_m;
%   steps, newton_iterations, seconds, t (s) and disk (disk y, z over time, m).
here = fileparts(mfilename('fullpath'));
if nargin < 1 || isempty(params_file), params_file = fullfile(here, 'jeffcott.json'); end
if nargin < 2 || isempty(root), root = fullfile(here, '..', '..', '..', '..'); end
p = jsondecode(fileread(params_file));

% The bearings: one element (fitted laws), one warm-start state per bearing.
c = ehl_case(fullfile(root, 'examples', '7006.toml'), p.speed_rpm);
e = ehl_element('fitted', c, fullfile(root, 'crates', 'ehl-bearing-py', 'tests', 'data', ...
                'fitted_7006_3000rpm_harmonic.json'));
bearing(1) = struct('dofs', [1 4 5], 'signs', [1; 1; 1], 'state', ehl_state());
bearing(2) = struct('dofs', [1 6 7], 'signs', [-1; 1; 1], 'state', ehl_state());  % mirrored
offset = [p.preload_approach_m; 0; 0];
W = p.speed_rpm * pi / 30;

% The rotor's matrices.
n = 7;
md = p.disk_mass_kg; mj = p.journal_mass_kg; ks = p.shaft_stiffness_n_m;
M = diag([md + 2 * mj, md, md, mj, mj, mj, mj]);
D = diag([p.axial_damping_n_s_m, p.disk_damping_n_s_m * [1 1], p.journal_damping_n_s_m * [1 1 1 1]]);
K = zeros(n);
for pair = [2 4; 3 5; 2 6; 3 7]'
  i = pair(1); j = pair(2);
  K([i j], [i j]) = K([i j], [i j]) + ks * [1 -1; -1 1];
end
f_const = zeros(n, 1);
f_const(2) = p.disk_force_y_n;
me = p.unbalance_kg_m;
unbalance = @(t) me * W^2 * [0; cos(W * t); sin(W * t); 0; 0; 0; 0];

  % Bearing forces on the rotor (sum of L'*R) and their tangents, at rotor state (q, qd).
  function [f, Kt, Ct] = bearings(q, qd)
    f = zeros(n, 1); Kt = zeros(n); Ct = zeros(n);
    for b = 1:2
      k = bearing(b).dofs; s = bearing(b).signs;
      y = [offset + s .* q(k); 0; 0];
      yd = [s .* qd(k); 0; 0];
      [R, Kb, Cb] = ehl_evaluate(e, y, yd, W, 0, 0, bearing(b).state);
      f(k) = f(k) + s .* R(1:3);
      Kt(k, k) = Kt(k, k) + (s * s') .* Kb(1:3, 1:3);
      Ct(k, k) = Ct(k, k) + (s * s') .* Cb(1:3, 1:3);
    end
  end

tic;
% Static equilibrium at speed: K*q + f_b(q, 0) = f_const, by Newton from q = 0.
q = zeros(n, 1);
for it = 1:100
  [fb, Kt] = bearings(q, zeros(n, 1));
  r = K * q + fb - f_const;
  if max(abs(r)) <= 1e-10 * max(1, max(abs(f_const))), break; end
  q = q - (K + Kt) \ r;
end
static_q = q;

% Newmark's average acceleration (beta = 1/4, gamma = 1/2), bearing forces implicit.
h = p.step_s;
steps = round(p.duration_s / h);
c0 = 4 / h^2; c1 = 2 / h;
v = zeros(n, 1);
a = M \ (f_const + unbalance(0) - D * v - K * q - bearings(q, v));
disk = zeros(steps + 1, 2);
disk(1, :) = q(2:3)';
iterations = 0;
for step = 1:steps
  t = step * h;
  f = f_const + unbalance(t);
  q1 = q + h * v + 0.5 * h^2 * a;          % predictor
  for it = 1:30
    a1 = c0 * (q1 - q) - c0 * h * v - a;   % = (q1 - q)/(beta h^2) - v/(beta h) - (1/(2 beta) - 1) a
    v1 = v + 0.5 * h * (a + a1);
    [fb, Kt, Ct] = bearings(q1, v1);
    r = M * a1 + D * v1 + K * q1 + fb - f;
    dq = (c0 * M + c1 * (D + Ct) + K + Kt) \ r;
    q1 = q1 - dq;
    iterations = iterations + 1;
    if max(abs(dq)) <= 1e-13, break; end
  end
  a1 = c0 * (q1 - q) - c0 * h * v - a;
  v = v + 0.5 * h * (a + a1);
  a = a1;
  q = q1;
  disk(step + 1, :) = q(2:3)';
  journal(step + 1, :) = q([4 7])'; %#ok<AGROW>
end
seconds = toc;

% 1x amplitudes over the last revolutions.
t = (0:steps)' * h;
per_rev = round(2 * pi / W / h);
last = (steps + 2 - per_rev * p.revolutions_measured):(steps + 1);
amp = @(x) 2 / numel(x) * abs(sum((x - mean(x)) .* exp(-1i * W * t(last))));
result = struct('amplitude_disk_y_m', amp(disk(last, 1)), ...
                'amplitude_disk_z_m', amp(disk(last, 2)), ...
                'amplitude_journal_a_y_m', amp(journal(last, 1)), ...
                'amplitude_journal_b_z_m', amp(journal(last, 2)), ...
                'static_disk_y_m', static_q(2), 'steps', steps, ...
                'newton_iterations', iterations, 'seconds', seconds, 't', t, 'disk', disk);
ehl_free(c, e, bearing(1).state, bearing(2).state);
end
