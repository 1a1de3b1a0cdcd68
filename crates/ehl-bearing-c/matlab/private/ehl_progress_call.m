function stop = ehl_progress_call(fn, json)
%EHL_PROGRESS_CALL  Calls the user's progress function with the decoded event; an error in it
%   is kept (EHL_PROGRESS_ERROR) and cancels the computation, to be raised afterwards as the
%   user's own error.
try
  stop = fn(jsondecode(json));
  stop = ~isempty(stop) && logical(stop(1));
catch err
  ehl_progress_error(err);
  stop = true;
end
end
