function ch = ehl_characterize(c, method, progress)
%EHL_CHARACTERIZE  Characterize the bearing of case C (the coupled EHL loop).
%   CH = EHL_CHARACTERIZE(C, METHOD) with METHOD 'hertz', 'synthetic', 'quasi-static' or
%   'harmonic' ('' or omitted: the case file's method, else quasi-static). The EHL methods take
%   seconds to minutes.
%   CH = EHL_CHARACTERIZE(C, METHOD, PROGRESS) calls STOP = PROGRESS(EVENT) for each loop event
%   (a struct: event = 'iteration_started' | 'contact_done' | 'iteration_done', ...); a true
%   STOP cancels (error ehl:cancelled).
%   CH is a struct: id, type, converged, iterations, displacement (5x1), stiffness (5x5),
%   report (the characterization report as a struct, SI). EHL_ELEMENT(CH) gives its force
%   element. Release it with EHL_FREE.
if nargin < 2, method = ''; end
if nargin < 3, progress = []; end
[id, json] = ehl_mex_progress(progress, 'characterize', c, method);
report = jsondecode(json);
ch = struct('id', id, 'type', 'ehl_characterization', 'converged', report.converged, ...
            'iterations', report.iterations, ...
            'displacement', struct2vec(report.displacement), ...
            'stiffness', report.stiffness_ehl, 'report', report);
end

function v = struct2vec(d)
v = [d.x; d.y; d.z; d.theta_y; d.theta_z];
end
