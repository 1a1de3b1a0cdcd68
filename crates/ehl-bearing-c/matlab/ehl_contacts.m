function [loads, approaches] = ehl_contacts(e_or_state)
%EHL_CONTACTS  Per-ball contact loads (N) and approaches (m) of the last evaluation.
%   [LOADS, APPROACHES] = EHL_CONTACTS(E) for the element's own state, or EHL_CONTACTS(STATE):
%   Zx2 arrays, columns [inner, outer].
s = e_or_state;
if isstruct(s), s = s.state; end
[loads, approaches] = ehl_mex('contacts', s);
end
