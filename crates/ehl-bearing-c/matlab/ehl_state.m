function s = ehl_state()
%EHL_STATE  A new warm-start state for EHL_EVALUATE (one per bearing and caller); release it
%   with EHL_FREE.
s = ehl_mex('state');
end
