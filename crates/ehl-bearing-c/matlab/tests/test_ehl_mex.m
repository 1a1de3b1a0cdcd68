function test_ehl_mex(root, reference_file)
%TEST_EHL_MEX  The MEX interface against the Rust library's reference numbers, to round-off,
%   and its error paths. ROOT is the repository root, REFERENCE_FILE the output of
%   `cargo run --release -p ehl-bearing-c --example write_reference -- FILE`.
%   Prints 'N passed, M failed' and raises an error if any check failed.
global ehl_passed ehl_failed
ehl_passed = 0; ehl_failed = 0;
tol = 1e-12;

c = ehl_case(fullfile(root, 'examples', '7006.toml'));
c3000 = ehl_case(fullfile(root, 'examples', '7006.toml'), 3000);
check(c.ball_count == 11 && abs(c.ball_diameter_m - 7e-3) < 1e-15, 'case struct');
check(abs(c3000.inner_speed_rad_s - 100 * pi) < 1e-9, 'case at 3000 rpm');
events = {};
ch = ehl_characterize(c, 'synthetic', @(ev) record_event(ev));
els.dry = ehl_element('hertz', c);
els.fitted = ehl_element('fitted', c3000, fullfile(root, 'crates', 'ehl-bearing-py', 'tests', 'data', ...
                         'fitted_7006_3000rpm_harmonic.json'));
els.trend = ehl_element('trend', fullfile(root, 'docs', 'figures', 'study_7006_quasi_static_trends.json'));
els.synthetic = ehl_element(ch);
check(strcmp(els.fitted.kind, 'fitted') && els.fitted.has_damping, 'fitted element struct');
check(strcmp(els.trend.kind, 'trend') && ~els.trend.has_damping, 'trend element struct');
check(strcmp(els.dry.kind, 'dry'), 'dry element struct');
n_events = ehl_progress_count();
check(n_events > 0, sprintf('progress events: %d', n_events));

% Every number of the reference file.
fid = fopen(reference_file, 'r');
if fid < 0, error('cannot read %s', reference_file); end
evals = 0;
lineno = 0;
while true
  line = fgetl(fid);
  if ~ischar(line), break; end
  lineno = lineno + 1;
  if isempty(line) || line(1) == '#', continue; end
  parts = strsplit(strtrim(line), ' ');
  kind = parts{1};
  name = parts{2};
  v = str2double(parts(3:end));
  where = sprintf('reference line %d (%s %s)', lineno, kind, name);
  switch kind
    case 'eval'
      e = els.(name);
      [R, K, C, info] = ehl_evaluate(e, v(1:5), v(6:10), v(11), v(12), v(13));
      close_to(R, v(14:18)', tol, [where ' reaction']);
      close_to(K, reshape(v(19:43), 5, 5)', tol, [where ' stiffness']);
      close_to(C, reshape(v(44:68), 5, 5)', tol, [where ' damping']);
      close_to(info.cage_speed_rad_s, v(69), tol, [where ' operating cage speed']);
      evals = evals + 1;
    case 'cage'
      close_to(ehl_cage_speed(els.(name), v(1), v(2)), v(3), tol, [where ' cage speed']);
    case 'equilibrium'
      if strcmp(name, 'fitted'), cc = c3000; else, cc = c; end
      [q, K] = ehl_equilibrium(els.(name), cc);
      close_to(q, v(1:5)', tol, [where ' displacement']);
      close_to(K, reshape(v(6:30), 5, 5)', tol, [where ' stiffness']);
    case 'summary'
      check(ch.converged == v(1) && ch.iterations == v(2), [where ' converged, iterations']);
      close_to(ch.displacement, v(3:7)', tol, [where ' displacement']);
      close_to(ch.stiffness, reshape(v(8:32), 5, 5)', tol, [where ' stiffness']);
  end
end
fclose(fid);
check(evals == 16, sprintf('evaluations compared: %d (16 expected)', evals));

% Contacts, coefficients, ROSS table.
[loads, appr] = ehl_contacts(els.synthetic);
check(isequal(size(loads), [11 2]) && all(loads(:, 1) > 0) && all(appr(:, 1) > 0), 'contacts');
[co, csv] = ehl_coefficients(c, [3000 5000], 'element', els.dry);
check(numel(co) == 2 && isequal(size(co(1).stiffness), [5 5]) && co(1).inner_speed_rpm == 3000, ...
      'coefficients struct array');
check(ischar(csv) && numel(strsplit(strtrim(csv), sprintf('\n'))) >= 3, 'ROSS table');

% The embedded law maps (the first the seed oil's: M 120-4000, 17 nodes, log).
maps = ehl_law_maps();
if iscell(maps), first = maps{1}; last = maps{end}; else, first = maps(1); last = maps(end); end
check(numel(maps) >= 13 && strcmp(first.law, 'quasi-static') && strcmp(last.law, 'harmonic') ...
      && first.spec.axis(1).min == 120 && first.spec.axis(1).nodes == 17, 'law maps');

% Error paths: MATLAB errors with the library's message and an identifier per status.
expect_error(@() ehl_case(sprintf('this is [ not toml =\n')), 'ehl:input', 'toml');
expect_error(@() ehl_case(fullfile(root, 'no_such_case.toml')), 'ehl:input', 'no_such_case');
expect_error(@() ehl_case(fullfile(root, 'examples', '7006.toml'), NaN), 'ehl:argument', 'rpm');
q = [2e-5 0 0 0 0];
expect_error(@() ehl_evaluate(els.dry, [q(1:2) NaN 0 0], [], 100), 'ehl:argument', 'input->displacement[2]');
expect_error(@() ehl_evaluate(els.dry, [1 2 3], [], 100), 'ehl:usage', '5 elements');
expect_error(@() ehl_evaluate(els.dry, q, [], Inf), 'ehl:argument', 'inner_speed_rad_s');
R = ehl_evaluate(els.dry, q, [], 100);
check(R(1) > 0, 'the state is usable after errors');
expect_error(@() ehl_evaluate(c, q, [], 100), 'ehl:usage', 'is an ehl-bearing case');
expect_error(@() ehl_characterize(c, 'magic'), 'ehl:input', 'unknown method');
expect_error(@() ehl_characterize(c, 'synthetic', @(ev) true), 'ehl:cancelled', 'cancelled');
expect_error(@() ehl_characterize(c, 'synthetic', @(ev) error('my:stop', 'stopped by the test')), ...
             'my:stop', 'stopped by the test');
expect_error(@() ehl_element('fitted', c, '{"not": "a report"}'), 'ehl:input', 'report');
expect_error(@() ehl_element('trend', '[]'), 'ehl:input', 'trend');
gone = ehl_element('hertz', c);
ehl_free(gone);
expect_error(@() ehl_evaluate(gone, q, [], 100), 'ehl:usage', 'no ehl-bearing object');
expect_error(@() ehl_mex('no_such_command'), 'ehl:usage', 'unknown command');

ehl_free('all');
check(ehl_mex('count') == 0, 'ehl_free(''all'') releases every object');
fprintf('MEX interface tests: %d passed, %d failed\n', ehl_passed, ehl_failed);
fprintf('%d passed, %d failed\n', ehl_passed, ehl_failed);
if ehl_failed > 0
  error('ehl:test', '%d MEX interface checks failed', ehl_failed);
end
end

function stop = record_event(ev)
ehl_progress_count(1);
stop = ~isstruct(ev) || ~isfield(ev, 'event');
end

function n = ehl_progress_count(add)
persistent count
if isempty(count), count = 0; end
if nargin > 0, count = count + add; end
n = count;
end

function check(ok, what)
global ehl_passed ehl_failed
if ok
  ehl_passed = ehl_passed + 1;
else
  ehl_failed = ehl_failed + 1;
  fprintf(2, 'FAIL: %s\n', what);
end
end

function close_to(got, want, tol, what)
scale = max(abs(want(:)));
d = max(abs(got(:) - want(:)));
check(isequal(size(got), size(want)) && d <= tol * scale, ...
      sprintf('%s: largest difference %.3g (scale %.3g)', what, d, scale));
end

function expect_error(f, id, text)
try
  f();
  check(false, sprintf('no error, expected %s', id));
catch err
  check(strcmp(err.identifier, id) && ~isempty(strfind(err.message, text)), ...
        sprintf('expected %s containing "%s", got %s: %s', id, text, err.identifier, err.message));
end
end
