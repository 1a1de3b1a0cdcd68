function [q, K, C] = ehl_equilibrium(e, c)
%EHL_EQUILIBRIUM  Equilibrium of element E under the loads of case C at its speeds.
%   [Q, K, C] = EHL_EQUILIBRIUM(E, C): displacement Q (5x1, m and rad) where the element's
%   reactions carry the case's load-controlled DOFs (the others imposed), and K, C there (5x5).
[q, K, C] = ehl_mex('equilibrium', e, c);
end
